// Helpers shared by the embedding stages: input checks, the sample distance matrix, and the
// reflection state of a sample embedding relative to the surface.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "registry/stages.h"

namespace symembed {

// Throws InvalidInputError unless D is #S x #V, finite and non-negative, and samples are
// distinct valid vertex ids (#S >= 2).
void CheckEmbeddingInput(const EmbeddingInput& input);

// The #S x #S sample-to-sample distances D(:, samples), symmetrised ((A + A^T) / 2, because
// approximate geodesics such as fast marching are not exactly symmetric), zero diagonal.
Eigen::MatrixXd SampleDistances(const EmbeddingInput& input);

// The samples' input coordinates, #S x 3.
Eigen::MatrixXd SampleCoordinates(const EmbeddingInput& input);

// The reflection state of a sample embedding Ys (#S x dims): sign of det of the best orthogonal
// Procrustes fit from the samples' input coordinates to Ys, and the fit's conditioning (smallest
// over largest singular value of the cross-covariance, see ProcrustesFit). When the
// conditioning is small (below about 0.02) one axis of the input is barely related to any axis
// of the embedding and the sign says little (e.g. a pose whose front-back extent the embedding
// redistributes); per-neighbourhood fits are then more telling. Defined for dims == 3 only: a
// 2D embedding has no orientation relative to a 3D surface, so {+1, 0} for any other dims.
struct ReflectionState {
  int sign = 1;
  double conditioning = 0.0;
};
ReflectionState EmbeddingReflection(const EmbeddingInput& input, const Eigen::MatrixXd& Ys);

// "reflection -1 (Procrustes conditioning 0.0069)" for status messages.
std::string ReflectionText(const ReflectionState& state);

// The vertex ids that are not samples, ascending.
std::vector<int> NonSampleVertices(const EmbeddingInput& input);

}  // namespace symembed

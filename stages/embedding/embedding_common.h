// Helpers shared by the embedding stages: input checks, the sample distance matrix, and the
// reflection state of a sample embedding relative to the surface.
#pragma once

#include <Eigen/Core>
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

// Sign of det of the best orthogonal Procrustes fit from the samples' input coordinates to their
// embedding Ys (#S x dims). Defined for dims == 3 only: a 2D embedding has no orientation
// relative to a 3D surface, so +1 is reported for any other dims.
int EmbeddingReflection(const EmbeddingInput& input, const Eigen::MatrixXd& Ys);

// The vertex ids that are not samples, ascending.
std::vector<int> NonSampleVertices(const EmbeddingInput& input);

}  // namespace symembed

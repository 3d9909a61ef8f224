// Symmetry stage `plane3d`: reflective symmetry plane searched directly in the 3D embedding
// (the ablation baseline of `plane2d`).
//
// Starting planes through the sample centroid with normals along the three principal axes and
// along a Fibonacci set of directions on the hemisphere; each is refined by reflect / NN / refit
// iterations with a trimmed score (stages/symmetry/reflection_search.h); the winner minimises
// score + intrinsic_weight * intrinsic distortion of its self map (geodesic distances between
// samples should be preserved by a symmetry).
// [Mitra et al. 2006] Partial and approximate symmetry detection for 3D geometry.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "registry/types.h"
#include "stages/symmetry/reflection_search.h"

namespace symembed {

struct Plane3dOptions {
  ReflectionSearchOptions search;
  // Starting normals besides the principal axes (Fibonacci points on the hemisphere).
  int num_directions = 32;
  static constexpr Range kNumDirections = Range::Closed(0, 10000);
  IntrinsicCheckOptions intrinsic;
  // Threads the starting planes are refined on (0: all cores). The result does not depend on it.
  int threads = 0;
  static constexpr Range kThreads = Range::Closed(0, 256);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    ReflectionSearchOptions::Fields(self.search, visit);
    visit("num_directions", self.num_directions, kNumDirections);
    IntrinsicCheckOptions::Fields(self.intrinsic, visit);
    visit("threads", self.threads, kThreads);
  }
  bool IsValid(std::string* error) const {
    return search.IsValid(error) && NoViolation(FieldViolation(*this), error);
  }
};

// The best refined candidate plane on the sample positions P (#S x 3, index built on P),
// intrinsic_check that of the #S x #S sample distances: minimises score + intrinsic_weight *
// distortion, returned through *total and *intrinsic (+inf total when every candidate was
// rejected). *iterations adds up the refinement iterations.
ReflectionFit SearchPlanes3d(const Eigen::MatrixXd& P, const KnnIndex& index,
                             const IntrinsicCheck& intrinsic_check, const Plane3dOptions& options,
                             double* total, double* intrinsic, int* iterations);

// D: #S x #V geodesic distances from the samples; samples: #S >= 4 vertex ids; Y: #V x 3
// embedding. Returns the plane in the coordinates of Y, the sample self map, per-sample
// confidence and the trimmed score. Throws InvalidInputError on inconsistent shapes, ConfigError
// on invalid options.
SymmetryResult DetectSymmetryPlane3d(const Eigen::MatrixXd& D, const std::vector<int>& samples,
                                     const Eigen::MatrixXd& Y, const Plane3dOptions& options);

}  // namespace symembed

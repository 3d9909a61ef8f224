// The matching stage `deformed` (stages/matching/register.cpp): the source embedding bent
// smoothly onto the target's, then the nearest neighbour as in `nearest`.
//
// Two poses of one body give canonical embeddings that differ where the body is not isometric
// and where LS-MDS keeps some of the pose (an arm held against the side lands elsewhere than an
// arm held out), and two bodies differ by their proportions. Nearest neighbours then send points
// of the arm to the torso. This stage first moves the source embedding by a displacement field
// that is smooth along the source surface, u = Phi D, with Phi the first k eigenfunctions of the
// source's Laplace-Beltrami operator and D a k x 3 matrix of coefficients: a non-rigid ICP in
// the embedding space whose deformation lives in the spectral basis, so that the arm moves
// without dragging the torso it touches in the embedding. Per iteration:
//   correspondences on the samples, both ways (each source sample to its nearest target sample,
//   each target sample to its nearest moved source sample, with normals as in `nearest`); then
//   D = argmin  mean_i |y_i + (Phi D)_i - x_t(i)|^2 + mean_j |y_s(j) + (Phi D)_s(j) - x_j|^2
//             + smoothness * sum_l lambda_l |D_l|^2,
// the last term being the Dirichlet energy of u on the source (Phi is M-orthonormal), with the
// eigenvalues of the unit-area surfaces the embeddings come from. k grows from k_start to k_end
// (coarse to fine, as in ZoomOut). Both directions of correspondence keep the source from
// shrinking onto part of the target.
// [Besl & McKay 1992] ICP; [Melzi et al. 2019] ZoomOut (the spectral upsampling schedule);
// [Yoshiyasu et al. 2016] the nearest-neighbour correspondence of aligned embeddings.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/fmap/zoomout.h"
#include "core/matching/nearest.h"
#include "core/range.h"
#include "core/spectral.h"

namespace symembed {

struct DeformOptions {
  int k_start = 4;  // first basis size
  static constexpr Range kKStart = Range::Closed(1, 1000);
  int k_end = 20;  // last basis size (>= k_start)
  static constexpr Range kKEnd = Range::Closed(1, 1000);
  int step = 4;  // increment of k; k_end is always the last size
  static constexpr Range kStep = Range::Closed(1, 1000);
  int iterations = 2;  // ICP iterations per basis size
  static constexpr Range kIterations = Range::Closed(1, 1000);
  double smoothness = 0.01;  // weight of the Dirichlet energy
  static constexpr Range kSmoothness = Range::AtLeast(0.0);
  int samples = 1000;  // samples of each shape the fit runs on (fewer: all there are)
  static constexpr Range kSamples = Range::Closed(1, 1000000);
  // Weight of the normals in the correspondences and the final match (MatchNearest).
  double normal_weight = kDefaultNormalWeight;
  static constexpr Range kNormalWeight = Range::AtLeast(0.0);
  int threads = 1;  // of the final nearest-neighbour query (0: DefaultThreadCount())
  static constexpr Range kThreads = Range::Closed(0, 256);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    BasisSizeFields(self, visit);
    visit("iterations", self.iterations, kIterations);
    visit("smoothness", self.smoothness, kSmoothness);
    visit("samples", self.samples, kSamples);
    visit("normal_weight", self.normal_weight, kNormalWeight);
    visit("threads", self.threads, kThreads);
  }
  bool IsValid(std::string* error) const;
};

struct DeformResult {
  Eigen::MatrixX3d Y;            // #Vs x 3 moved source embedding
  // #Vs x 3 unit normals of the moved surface (Y on F); the source's normals when
  // normal_weight is 0 (the fit then does not use them).
  Eigen::MatrixX3d N;
  double residual_before = 0.0;  // mean squared correspondence distance, first iteration
  double residual_after = 0.0;   // the same, last iteration
};

// source: the source's embedded points (#Vs rows) with its faces F (for the normals of the moved
// surface); basis: the source's Laplace-Beltrami basis with at least k_end eigenpairs and #Vs
// rows; source_samples, target_samples: vertex ids the fit runs on (the first options.samples
// of each); target: the target's embedded points, already rotated. Throws InvalidInputError for
// inconsistent inputs, ConfigError for invalid options.
DeformResult DeformSource(const EmbeddedPoints& source, const Eigen::MatrixX3i& F,
                          const LaplaceBasis& basis, const std::vector<int>& source_samples,
                          const EmbeddedPoints& target, const std::vector<int>& target_samples,
                          const DeformOptions& options);

}  // namespace symembed

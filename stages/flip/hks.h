// Flip scorer `hks`: heat kernel signatures compared through each candidate's nearest-neighbour
// map.
//
// [Sun et al. 2009] A concise and provably informative multi-scale signature based on heat
// diffusion: HKS(x, t) = sum_i exp(-lambda_i t) phi_i(x)^2 from the Laplace-Beltrami eigenpairs
// (core/spectral.h; the shape's basis, shared with the refine stages). HKS is
// intrinsic, so it cannot tell left from right, but it tells head from tail and top from
// bottom, which is exactly the ambiguity left by the canonical frame. Signatures are divided by
// the heat trace sum_i exp(-lambda_i t) (scale normalisation on unit-area shapes) and compared in
// log scale at times log-spaced in [4 ln 10 / lambda_max, 4 ln 10 / lambda_1] shared by both
// shapes of the pair.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

#include "core/range.h"
#include "core/spectral.h"

namespace symembed {

struct HksFlipOptions {
  // Laplace-Beltrami eigenpairs used.
  int eigenpairs = 50;
  static constexpr Range kEigenpairs = Range::Closed(2, 10000);
  // Number of diffusion times.
  int num_times = 16;
  static constexpr Range kNumTimes = Range::Closed(1, 1000);
  int threads = 1;  // 0: DefaultThreadCount()
  static constexpr Range kThreads = Range::Closed(0, 256);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("eigenpairs", self.eigenpairs, kEigenpairs);
    visit("num_times", self.num_times, kNumTimes);
    visit("threads", self.threads, kThreads);
  }
  bool IsValid(std::string* error) const { return NoViolation(FieldViolation(*this), error); }
};

// times: T >= 1 diffusion times. Returns #V x T, each column divided by its heat trace.
Eigen::MatrixXd HeatKernelSignature(const LaplaceBasis& basis, const Eigen::VectorXd& times);

// The T times shared by a pair: log-spaced in [4 ln 10 / lambda_max, 4 ln 10 / lambda_1] with
// lambda_1 the smallest eigenvalue above 1e-8 lambda_max and lambda_max the largest, each the
// mean over the two bases.
Eigen::VectorXd HksTimes(const LaplaceBasis& a, const LaplaceBasis& b, int num_times);

// Ys, Yt: canonical embeddings; the bases of the two surfaces (same number of eigenpairs);
// as: #Vs source vertex areas. Score k = area-weighted mean over source vertices of the mean
// over times of |log HKS_s(v) - log HKS_t(T_k(v))|.
std::array<double, 4> HksFlipScores(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                    const LaplaceBasis& source, const LaplaceBasis& target,
                                    const HksFlipOptions& options);

}  // namespace symembed

// Least-squares multidimensional scaling by SMACOF (majorization of raw stress).
//
// Minimises raw stress  sigma(X) = sum_{i<j} w_ij (d_ij - ||x_i - x_j||)^2  over X (n x dims)
// by the Guttman transform X <- V^+ B(X) X, which never increases stress. With uniform weights
// V^+ B(X) X = B(X) X / n; with weights w_ij = d_ij^-p the pseudo-inverse V^+ is applied through
// one dense Cholesky factorisation of V + 11^T / n.
//
// Acceleration, with stress still never increasing: each update tries, in order,
//  1. an Anderson-accelerated candidate built from the last `anderson_window` iterates and their
//     Guttman images [Walker & Ni 2011], kept only when it lowers stress (the safeguard of
//     [Peng et al. 2018]; on rejection the history restarts);
//  2. the relaxed update X + alpha (G(X) - X), 1 <= alpha < 2, which keeps the quadratic
//     majorizer at or below sigma(X) (the majorizer is symmetric about G(X) in the V-norm)
//     [de Leeuw & Heiser 1980], kept when stress does not increase;
//  3. the plain Guttman step G(X). If even that increases stress (rounding at a stationary
//     point) the iteration stops at the previous iterate.
// The recorded stress history is therefore non-increasing. An accelerated step whose relative
// change is below tolerance is confirmed by one non-accelerated step before stopping.
// Each pair's distance is computed once per stress evaluation (O(n^2 dims), parallel over
// fixed lanes so results do not depend on the thread count).
//
// [de Leeuw 1977] Applications of convex analysis to multidimensional scaling.
// [de Leeuw & Heiser 1980] Multidimensional scaling with restrictions on the configuration.
// [Borg & Groenen 2005] Modern Multidimensional Scaling, ch. 8.
// [Walker & Ni 2011] Anderson acceleration for fixed-point iterations.
// [Peng et al. 2018] Anderson acceleration for geometry optimization and physics simulation.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/range.h"

namespace symembed {

struct SmacofOptions {
  // Stop when (sigma_{k-1} - sigma_k) / sigma_{k-1} < tolerance (that ratio is at most 1).
  double tolerance = 1e-6;
  static constexpr Range kTolerance = Range::Closed(0.0, 1.0);
  // Stop after this many Guttman updates even when not converged.
  int max_iterations = 1000;
  static constexpr Range kMaxIterations = Range::AtLeast(0);
  // Weights w_ij = d_ij^-weight_power (0: uniform weights, the fast path). Pairs with d_ij = 0
  // get weight 0 when weight_power > 0.
  double weight_power = 0.0;
  static constexpr Range kWeightPower = Range::Closed(0.0, 8.0);
  // Over-relaxation factor alpha (1: plain Guttman steps; below 2 the relaxed step keeps the
  // majorizer at or below the stress).
  double relaxation = 1.9;
  static constexpr Range kRelaxation = Range::ClosedOpen(1.0, 2.0);
  // Anderson acceleration window m (0: off).
  int anderson_window = 5;
  static constexpr Range kAndersonWindow = Range::Closed(0, 20);
  // Threads for the O(n^2) passes (0: DefaultThreadCount()).
  int threads = 0;
  static constexpr Range kThreads = Range::AtLeast(0);

  // The options as a config names them (core/range.h), besides threads.
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("tolerance", self.tolerance, kTolerance);
    visit("max_iterations", self.max_iterations, kMaxIterations);
    visit("weight_power", self.weight_power, kWeightPower);
    visit("relaxation", self.relaxation, kRelaxation);
    visit("anderson_window", self.anderson_window, kAndersonWindow);
  }

  // Whether every option lies in its range; else the first violation, naming the field.
  bool IsValid(std::string* error) const;
};

struct SmacofResult {
  Eigen::MatrixXd X;                   // n x dims, centred
  std::vector<double> stress_history;  // raw stress of iterate k = 0 (init) .. iterations
  double stress = 0.0;                 // raw stress of X
  double normalized_stress = 0.0;      // sqrt(stress / sum_{i<j} d_ij^2)
  int iterations = 0;                  // accepted updates
  int evaluations = 0;                 // stress evaluations (O(n^2) passes), init included
  bool converged = false;              // tolerance reached before max_iterations
};

// D: n x n symmetric dissimilarities (zero diagonal, non-negative; only the symmetric part is
// used), init: n x dims starting configuration (dims >= 1). Throws InvalidInputError on bad
// shapes or non-finite/negative D, ConfigError on invalid options.
SmacofResult Smacof(const Eigen::MatrixXd& D, const Eigen::MatrixXd& init,
                    const SmacofOptions& options = {});

// Raw stress sum_{i<j} (d_ij - ||x_i - x_j||)^2 with uniform weights. D: n x n, X: n x dims.
double RawStress(const Eigen::MatrixXd& D, const Eigen::MatrixXd& X, int threads = 0);

// sqrt(RawStress / sum_{i<j} d_ij^2) (0 when D is zero).
double NormalizedStress(const Eigen::MatrixXd& D, const Eigen::MatrixXd& X, int threads = 0);

// X centred and scaled by the s > 0 minimising sum_{i<j} (d_ij - s ||x_i - x_j||)^2, so that a
// configuration in other units (e.g. surface coordinates) starts at the distances' scale.
Eigen::MatrixXd ScaleToDistances(const Eigen::MatrixXd& D, const Eigen::MatrixXd& X);

}  // namespace symembed

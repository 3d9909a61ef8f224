// Least-squares multidimensional scaling by SMACOF (majorization of raw stress).
//
// Minimises raw stress  sigma(X) = sum_{i<j} w_ij (d_ij - ||x_i - x_j||)^2  over X (n x dims)
// by the Guttman transform X <- V^+ B(X) X, which never increases stress. With uniform weights
// V^+ B(X) X = B(X) X / n; with weights w_ij = d_ij^-p the pseudo-inverse V^+ is applied through
// one dense Cholesky factorisation of V + 11^T / n.
//
// Acceleration: the relaxed update X <- X + alpha (G(X) - X), 1 <= alpha < 2, keeps the value of
// the quadratic majorizer at or below sigma(X) (the majorizer is symmetric about G(X) in the
// V-norm), so stress still never increases; a step whose stress is higher than the previous one
// (rounding) is replaced by the plain Guttman step, and if that is also higher the iteration stops
// at the previous iterate. The recorded stress history is therefore non-increasing.
//
// [de Leeuw 1977] Applications of convex analysis to multidimensional scaling.
// [de Leeuw & Heiser 1980] Multidimensional scaling with restrictions on the configuration.
// [Borg & Groenen 2005] Modern Multidimensional Scaling, ch. 8.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace symembed {

struct SmacofOptions {
  // Stop when (sigma_{k-1} - sigma_k) / sigma_{k-1} < tolerance.
  double tolerance = 1e-6;
  // Stop after this many Guttman updates even when not converged.
  int max_iterations = 1000;
  // Weights w_ij = d_ij^-weight_power (0: uniform weights, the fast path). Pairs with d_ij = 0
  // get weight 0 when weight_power > 0.
  double weight_power = 0.0;
  // Over-relaxation factor alpha in [1, 2) (1: plain SMACOF).
  double relaxation = 1.9;
  // Threads for the O(n^2) passes (0: DefaultThreadCount()).
  int threads = 0;

  bool IsValid(std::string* error) const;
};

struct SmacofResult {
  Eigen::MatrixXd X;                   // n x dims, centred
  std::vector<double> stress_history;  // raw stress of iterate k = 0 (init) .. iterations
  double stress = 0.0;                 // raw stress of X
  double normalized_stress = 0.0;      // sqrt(stress / sum_{i<j} d_ij^2)
  int iterations = 0;                  // Guttman updates performed
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

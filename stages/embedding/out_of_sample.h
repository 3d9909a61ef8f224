// Out-of-sample placement for a least-squares MDS embedding.
//
// Each query point a is placed independently by minimising its stress to its k nearest samples
// (nearest by the given distances), sum_j (d_aj - ||y - y_j||)^2, over y, with the samples
// fixed. The minimisation starts at the barycentre of the k samples weighted by 1/d_aj^2 and
// runs Levenberg-Marquardt (Gauss-Newton steps on the residuals ||y - y_j|| - d_aj, damped
// until the stress does not increase). Gauss-Newton rather than the single-point Guttman
// update because the samples around a surface point are nearly coplanar and first-order
// updates converge very slowly along the normal. Queries run in parallel.
//
// [Borg & Groenen 2005] Modern Multidimensional Scaling, ch. 8 and 13.
// [Trosset & Priebe 2008] The out-of-sample problem for classical multidimensional scaling.
// [Nocedal & Wright 2006] Numerical Optimization, ch. 10 (Levenberg-Marquardt).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace symembed {

struct OutOfSampleOptions {
  int neighbors = 12;       // k nearest samples per query, <= 64 (clamped to #samples)
  int max_iterations = 20;  // Levenberg-Marquardt iterations per query
  // Stop when a step is shorter than tolerance * the mean distance to the k samples.
  double tolerance = 1e-7;
  int threads = 0;          // 0: DefaultThreadCount()

  bool IsValid(std::string* error) const;
};

// Ys: n x dims sample embedding (dims <= 8); D: n x m distances from each sample to each point; columns:
// the columns of D to place (all when empty). Returns (#columns or m) x dims.
// Throws InvalidInputError on mismatched shapes or bad distances, ConfigError on bad options.
Eigen::MatrixXd PlaceOutOfSample(const Eigen::MatrixXd& Ys, const Eigen::MatrixXd& D,
                                 const std::vector<int>& columns = {},
                                 const OutOfSampleOptions& options = {});

}  // namespace symembed

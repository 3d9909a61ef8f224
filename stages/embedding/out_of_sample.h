// Out-of-sample placement for a least-squares MDS embedding.
//
// Each query point a is placed independently by minimising its weighted stress to its k nearest
// samples (nearest by the given distances), sum_j w_aj (d_aj - ||y - y_j||)^2 with
// w_aj = (d_a1 / d_aj)^p (d_a1 the nearest distance), over y, with the samples fixed. With p = 2
// (default) every term is a squared relative error, so the nearest samples dominate and the
// placement is local; as a query approaches a sample its position tends to the sample's, and a
// query at distance 0 from a sample is placed exactly on it. With p = 0 all k distances count
// alike (plain stress): the embedding distorts short distances by a few percent of the long
// ones, and plain stress spreads that over the neighbourhood (on a synthetic quadruped with 300
// samples, a sample placed through this path moved by 1/3 of the sample spacing on average,
// and the distance of a vertex to its nearest sample was off by 52% on average against 13%
// with p = 2). The minimisation starts at the barycentre of the k samples weighted by 1/d_aj^2 and
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

#include "core/range.h"

namespace symembed {

struct OutOfSampleOptions {
  int neighbors = 12;  // k nearest samples per query (clamped to #samples)
  static constexpr Range kNeighbors = Range::Closed(1, 64);
  double weight_power = 2.0;  // p of the weights (d_a1 / d_aj)^p
  static constexpr Range kWeightPower = Range::Closed(0.0, 4.0);
  int max_iterations = 20;  // Levenberg-Marquardt iterations per query
  static constexpr Range kMaxIterations = Range::AtLeast(0);
  // Stop when a step is shorter than tolerance * the mean distance to the k samples.
  double tolerance = 1e-7;
  static constexpr Range kTolerance = Range::AtLeast(0.0);
  int threads = 0;  // 0: DefaultThreadCount()
  static constexpr Range kThreads = Range::AtLeast(0);

  bool IsValid(std::string* error) const;
};

// Ys: n x dims sample embedding (dims <= 8); D: n x m distances from each sample to each point;
// columns: the columns of D to place (all when empty). Returns (#columns or m) x dims. Throws
// InvalidInputError on mismatched shapes or bad distances, ConfigError on bad options.
Eigen::MatrixXd PlaceOutOfSample(const Eigen::MatrixXd& Ys, const Eigen::MatrixXd& D,
                                 const std::vector<int>& columns = {},
                                 const OutOfSampleOptions& options = {});

}  // namespace symembed

// Nearest neighbours among the rows of a dense matrix of any dimension (spectral embeddings:
// #V x k with k up to a few hundred); exact, up to single-precision rounding in high dimensions.
//
// Low dimensions use a FLANN single kd-tree. From kBruteForceMinDims dimensions on, a brute force
// in single precision (nearest_kernel.h: ||p||^2 - 2 q.p for tiles of queries against blocks of
// points, in registers) is used instead: M-orthonormal eigenvectors make a spectral embedding's
// covariance isotropic, so a kd-tree, which bounds distances by the few coordinates it splits
// on, prunes almost nothing at k ~ 100 and spends its time in per-point distance loops. The
// threshold is where the two cost the same with the earlier brute force (a matrix product, then
// the minimum); the kernel is faster already below it, but lowering the threshold would move the
// low-dimensional searches (the orientation flip term's first basis sizes, ZoomOut's early
// starts) to single precision and change their maps. The squared distance of the winner
// of the single-precision comparison is recomputed in double precision.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/flann_fwd.h"
#include "core/fmap/nearest_kernel.h"

namespace symembed {

class SpectralNearest {
 public:
  // Dimension from which kAuto uses the blocked brute force.
  static constexpr int kBruteForceMinDims = 20;
  enum class Method { kAuto, kKdTree, kBruteForce };

  // points: n x d, one point per row (copied). `ids` (optional, n entries): the id reported for
  // each row; by default the row index.
  explicit SpectralNearest(const Eigen::MatrixXd& points, std::vector<int> ids = {},
                           Method method = Method::kAuto);
  ~SpectralNearest();
  SpectralNearest(const SpectralNearest&) = delete;
  SpectralNearest& operator=(const SpectralNearest&) = delete;

  int dims() const { return dims_; }

  // For each row of queries (m x d): the id of its nearest point (ties to the lower row) and,
  // when sq_dist is given, the squared Euclidean distance to it. Thread-safe.
  void Query(const Eigen::MatrixXd& queries, std::vector<int>* nearest,
             std::vector<double>* sq_dist = nullptr) const;

 private:
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  void QueryBruteForce(const Eigen::MatrixXd& queries, std::vector<int>* rows) const;

  int dims_ = 0;
  RowMatrix points_;
  std::vector<int> ids_;
  std::unique_ptr<FlannL2Index> index_;  // low dimensions only
  PackedPoints packed_;  // brute force: the points in single precision, packed for the kernel
};

}  // namespace symembed

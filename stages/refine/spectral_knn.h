// Nearest neighbours among the rows of a dense matrix of any dimension (spectral embeddings:
// #V x k with k up to a few hundred); exact, up to single-precision rounding in high dimensions.
//
// Low dimensions use a FLANN single kd-tree. From kBruteForceMinDims dimensions on (the measured
// crossover on 5k vertices), a blocked brute force in single precision (one matrix product per
// block of queries, ||q||^2 + ||p||^2 - 2 q.p) is used instead: M-orthonormal eigenvectors make
// a spectral embedding's covariance isotropic, so a kd-tree, which bounds distances by the few
// coordinates it splits on, prunes almost nothing at k ~ 100 and spends its time in per-point
// distance loops (5,048 queries among 5,048 points at k = 120: 0.93 s CPU with the kd-tree,
// 0.20 s with the blocked product; BM_SpectralNearest in bench_refine). The squared distance of
// the winner of the single-precision comparison is recomputed in double precision.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

namespace flann {
template <typename T>
struct L2;
template <typename Distance>
class Index;
}  // namespace flann

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
  std::unique_ptr<flann::Index<flann::L2<double>>> index_;  // low dimensions only
  Eigen::MatrixXf points_f_;    // brute force: n x d single-precision copy
  Eigen::VectorXf sq_norms_f_;  // brute force: ||p||^2 per point
};

}  // namespace symembed

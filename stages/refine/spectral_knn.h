// Exact nearest neighbours among the rows of a dense matrix of any dimension (spectral
// embeddings: #V x k with k up to a few hundred), with a FLANN single kd-tree.
//
// Spectral embeddings of a surface lie near a 2-manifold, so a kd-tree stays far faster than brute
// force even at k ~ 100.
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

class SpectralKdTree {
 public:
  // points: n x d, one point per row (copied). `ids` (optional, n entries): the id reported for
  // each row; by default the row index.
  explicit SpectralKdTree(const Eigen::MatrixXd& points, std::vector<int> ids = {});
  ~SpectralKdTree();
  SpectralKdTree(const SpectralKdTree&) = delete;
  SpectralKdTree& operator=(const SpectralKdTree&) = delete;

  int dims() const { return dims_; }

  // For each row of queries (m x d): the id of its nearest point and, when sq_dist is given, the
  // squared Euclidean distance to it. Thread-safe.
  void Query(const Eigen::MatrixXd& queries, std::vector<int>* nearest,
             std::vector<double>* sq_dist = nullptr) const;

 private:
  using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  int dims_ = 0;
  RowMatrix points_;
  std::vector<int> ids_;
  std::unique_ptr<flann::Index<flann::L2<double>>> index_;
};

}  // namespace symembed

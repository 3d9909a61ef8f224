// Exact k-nearest-neighbour queries on a fixed point set (FLANN kd-tree), and the nearest point
// alone by a kd-tree of its own in up to kMaxNearestKdDims dimensions (nearest_kd.h).
//
// [Muja & Lowe 2014] Scalable nearest neighbor algorithms for high dimensional data. A single
// kd-tree (KDTreeSingleIndex) is exact and fast in low dimension (2D and 3D embeddings).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <mutex>
#include <vector>

#include "core/flann_fwd.h"

namespace symembed {

class NearestSearch;

class KnnIndex {
 public:
  // points: #N x d (d >= 1, #N >= 1), copied. leaf_size: kd-tree leaf size.
  // Throws InvalidInputError for an empty or non-finite point set.
  explicit KnnIndex(const Eigen::MatrixXd& points, int leaf_size = 10);
  ~KnnIndex();
  KnnIndex(const KnnIndex&) = delete;
  KnnIndex& operator=(const KnnIndex&) = delete;

  int size() const { return num_points_; }
  int dims() const { return dims_; }

  // The k nearest points (k <= size()) of every row of queries (#Q x d), nearest first:
  // indices #Q x k point ids, distances #Q x k Euclidean distances (either may be null).
  // Queries are split over `threads` threads (0 = DefaultThreadCount()). Thread-safe.
  void Query(const Eigen::MatrixXd& queries, int k, Eigen::MatrixXi* indices,
             Eigen::MatrixXd* distances, int threads = 0) const;

  // The nearest point of every query row (#Q); its distance through *distances when given.
  // In up to kMaxNearestKdDims dimensions by NearestKd (nearest_kd.h; built on the first call),
  // which gives equally near points to the lowest index; otherwise Query with k = 1.
  std::vector<int> Nearest(const Eigen::MatrixXd& queries, Eigen::VectorXd* distances = nullptr,
                           int threads = 0) const;

 private:
  int num_points_ = 0;
  int dims_ = 0;
  int leaf_size_ = 10;
  std::vector<double> data_;  // row-major copy the index points into
  // Each tree is built on its first use: FLANN's by Query, NearestKd's by Nearest.
  mutable std::once_flag index_once_, nearest_once_;
  mutable std::unique_ptr<FlannL2Index> index_;
  mutable std::unique_ptr<NearestSearch> nearest_;
};

}  // namespace symembed

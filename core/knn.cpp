#include "core/knn.h"

#include <flann/flann.hpp>

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "core/nearest_kd.h"
#include "core/parallel.h"

namespace symembed {

KnnIndex::KnnIndex(const Eigen::MatrixXd& points, int leaf_size)
    : num_points_(static_cast<int>(points.rows())), dims_(static_cast<int>(points.cols())) {
  if (num_points_ < 1 || dims_ < 1) {
    throw InvalidInputError("KnnIndex: empty point set (" + std::to_string(num_points_) + " x " +
                            std::to_string(dims_) + ")");
  }
  if (!points.allFinite()) throw InvalidInputError("KnnIndex: non-finite point coordinates");
  SYMEMBED_CHECK(leaf_size >= 1, "leaf_size=" << leaf_size);
  data_.resize(static_cast<size_t>(num_points_) * dims_);
  for (int i = 0; i < num_points_; ++i) {
    for (int c = 0; c < dims_; ++c) data_[static_cast<size_t>(i) * dims_ + c] = points(i, c);
  }
  leaf_size_ = leaf_size;
}

KnnIndex::~KnnIndex() = default;

void KnnIndex::Query(const Eigen::MatrixXd& queries, int k, Eigen::MatrixXi* indices,
                     Eigen::MatrixXd* distances, int threads) const {
  SYMEMBED_CHECK(queries.cols() == dims_, "query dims " << queries.cols() << " != " << dims_);
  SYMEMBED_CHECK(k >= 1 && k <= num_points_, "k=" << k << " with " << num_points_ << " points");
  const int num_queries = static_cast<int>(queries.rows());
  if (indices) indices->resize(num_queries, k);
  if (distances) distances->resize(num_queries, k);
  if (num_queries == 0) return;
  std::call_once(index_once_, [&] {
    flann::Matrix<double> dataset(const_cast<double*>(data_.data()), num_points_, dims_);
    index_ = std::make_unique<FlannL2Index>(dataset, flann::KDTreeSingleIndexParams(leaf_size_));
    index_->buildIndex();
  });
  // Chunks of queries, each searched single-threaded by FLANN into its own buffers.
  constexpr int kChunk = 512;
  const int num_chunks = (num_queries + kChunk - 1) / kChunk;
  ParallelFor(
      num_chunks,
      [&](int chunk) {
        const int begin = chunk * kChunk;
        const int count = std::min(kChunk, num_queries - begin);
        std::vector<double> q(static_cast<size_t>(count) * dims_);
        for (int r = 0; r < count; ++r) {
          for (int c = 0; c < dims_; ++c) q[static_cast<size_t>(r) * dims_ + c] = queries(begin + r, c);
        }
        std::vector<size_t> idx(static_cast<size_t>(count) * k);
        std::vector<double> dist(static_cast<size_t>(count) * k);
        flann::Matrix<double> qm(q.data(), count, dims_);
        flann::Matrix<size_t> im(idx.data(), count, k);
        flann::Matrix<double> dm(dist.data(), count, k);
        flann::SearchParams params(flann::FLANN_CHECKS_UNLIMITED);
        params.cores = 1;
        params.sorted = true;
        index_->knnSearch(qm, im, dm, k, params);
        for (int r = 0; r < count; ++r) {
          for (int j = 0; j < k; ++j) {
            const size_t at = static_cast<size_t>(r) * k + j;
            if (indices) (*indices)(begin + r, j) = static_cast<int>(idx[at]);
            // flann::L2 returns squared distances.
            if (distances) (*distances)(begin + r, j) = std::sqrt(std::max(0.0, dist[at]));
          }
        }
      },
      threads);
}

std::vector<int> KnnIndex::Nearest(const Eigen::MatrixXd& queries, Eigen::VectorXd* distances,
                                   int threads) const {
  if (dims_ > kMaxNearestKdDims) {
    Eigen::MatrixXi idx;
    Eigen::MatrixXd dist;
    Query(queries, 1, &idx, distances ? &dist : nullptr, threads);
    if (distances) *distances = dist.col(0);
    return std::vector<int>(idx.data(), idx.data() + idx.rows());
  }
  SYMEMBED_CHECK(queries.cols() == dims_, "query dims " << queries.cols() << " != " << dims_);
  std::call_once(nearest_once_,
                 [&] { nearest_ = MakeNearestSearch(data_.data(), num_points_, dims_); });
  const int num_queries = static_cast<int>(queries.rows());
  std::vector<int> nearest(num_queries);
  if (distances) distances->resize(num_queries);
  constexpr int kChunk = 512;
  ParallelFor(
      (num_queries + kChunk - 1) / kChunk,
      [&](int chunk) {
        const int end = std::min(num_queries, (chunk + 1) * kChunk);
        double q[kMaxNearestKdDims];
        for (int r = chunk * kChunk; r < end; ++r) {
          for (int c = 0; c < dims_; ++c) q[c] = queries(r, c);
          double sq = 0.0;
          // Consecutive queries (vertices of a mesh, in its order) tend to be near each other:
          // the previous answer is the hint.
          nearest[r] = nearest_->Nearest(q, &sq, r > chunk * kChunk ? nearest[r - 1] : -1);
          if (distances) (*distances)(r) = std::sqrt(sq);
        }
      },
      threads);
  return nearest;
}

}  // namespace symembed

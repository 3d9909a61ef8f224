#include "stages/refine/spectral_knn.h"

#include <algorithm>
#include <flann/flann.hpp>
#include <limits>

#include "core/errors.h"

namespace symembed {

SpectralNearest::SpectralNearest(const Eigen::MatrixXd& points, std::vector<int> ids, Method method)
    : dims_(static_cast<int>(points.cols())), points_(points), ids_(std::move(ids)) {
  SYMEMBED_CHECK(points.rows() > 0 && points.cols() > 0,
                 "nearest-neighbour search needs at least one point");
  SYMEMBED_CHECK(
      ids_.empty() || ids_.size() == static_cast<size_t>(points.rows()),
      "nearest-neighbour search: " << ids_.size() << " ids for " << points.rows() << " points");
  if (method == Method::kBruteForce || (method == Method::kAuto && dims_ >= kBruteForceMinDims)) {
    points_f_ = points.cast<float>();
    sq_norms_f_ = points_f_.rowwise().squaredNorm();
    return;
  }
  flann::Matrix<double> data(points_.data(), points_.rows(), points_.cols());
  index_ =
      std::make_unique<flann::Index<flann::L2<double>>>(data, flann::KDTreeSingleIndexParams(16));
  index_->buildIndex();
}

SpectralNearest::~SpectralNearest() = default;

void SpectralNearest::QueryBruteForce(const Eigen::MatrixXd& queries,
                                      std::vector<int>* rows) const {
  // Blocks of queries keep the block x n product in cache-friendly size (n ~ 5k: 1 MB).
  constexpr int kBlock = 64;
  const int m = static_cast<int>(queries.rows());
  const Eigen::MatrixXf q = queries.cast<float>();
  Eigen::MatrixXf products;
  for (int begin = 0; begin < m; begin += kBlock) {
    const int b = std::min(kBlock, m - begin);
    products.noalias() = q.middleRows(begin, b) * points_f_.transpose();
    for (int r = 0; r < b; ++r) {
      // argmin_j ||p_j||^2 - 2 q.p_j (||q||^2 is common to all j).
      float best = std::numeric_limits<float>::infinity();
      int arg = 0;
      for (int j = 0; j < products.cols(); ++j) {
        const float d = sq_norms_f_(j) - 2.0f * products(r, j);
        if (d < best) {
          best = d;
          arg = j;
        }
      }
      (*rows)[begin + r] = arg;
    }
  }
}

void SpectralNearest::Query(const Eigen::MatrixXd& queries, std::vector<int>* nearest,
                            std::vector<double>* sq_dist) const {
  SYMEMBED_CHECK(queries.cols() == dims_,
                 "query has " << queries.cols() << " columns, points " << dims_);
  SYMEMBED_CHECK(nearest != nullptr, "nearest is null");
  const int m = static_cast<int>(queries.rows());
  nearest->assign(m, -1);
  if (sq_dist != nullptr) sq_dist->assign(m, 0.0);
  if (m == 0) return;
  if (index_ == nullptr) {
    QueryBruteForce(queries, nearest);
  } else {
    RowMatrix q = queries;
    std::vector<double> dists(m);
    flann::Matrix<double> query_matrix(q.data(), m, dims_);
    flann::Matrix<int> index_matrix(nearest->data(), m, 1);
    flann::Matrix<double> dist_matrix(dists.data(), m, 1);
    // Exact search: the single kd-tree ignores `checks` and is exact with eps = 0.
    flann::SearchParams params(flann::FLANN_CHECKS_UNLIMITED, 0.0f);
    index_->knnSearch(query_matrix, index_matrix, dist_matrix, 1, params);
  }
  for (int r = 0; r < m; ++r) {
    const int row = (*nearest)[r];
    if (sq_dist != nullptr) (*sq_dist)[r] = (queries.row(r) - points_.row(row)).squaredNorm();
    if (!ids_.empty()) (*nearest)[r] = ids_[row];
  }
}

}  // namespace symembed

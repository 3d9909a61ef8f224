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
  // Blocks of queries keep the n x block product in cache-friendly size (n ~ 5k: 1 MB). The
  // product is stored one query per column, so that each query's distances ||p_j||^2 - 2 q.p_j
  // (||q||^2 is common to all j) are contiguous: their minimum is a vectorized reduction, and the
  // first point that attains it (ties to the lower row) is found by a scan that stops there.
  constexpr int kBlock = 64;
  const int m = static_cast<int>(queries.rows());
  const Eigen::MatrixXf q = queries.cast<float>();
  Eigen::MatrixXf products;
  Eigen::VectorXf d;
  for (int begin = 0; begin < m; begin += kBlock) {
    const int b = std::min(kBlock, m - begin);
    products.noalias() = points_f_ * q.middleRows(begin, b).transpose();
    for (int r = 0; r < b; ++r) {
      d.noalias() = sq_norms_f_ - 2.0f * products.col(r);
      const float best = d.minCoeff();
      int arg = 0;
      const int last = static_cast<int>(d.size()) - 1;
      while (arg < last && !(d(arg) == best)) ++arg;  // bounded: NaN equals nothing
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

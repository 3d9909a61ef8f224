#include "core/fmap/spectral_knn.h"

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
    const Eigen::MatrixXf points_f = points.cast<float>();
    packed_ = PackPoints(points_f.data(), static_cast<int>(points_f.rows()), dims_,
                         static_cast<int>(points_f.rows()));
    return;
  }
  flann::Matrix<double> data(points_.data(), points_.rows(), points_.cols());
  index_ = std::make_unique<FlannL2Index>(data, flann::KDTreeSingleIndexParams(16));
  index_->buildIndex();
}

SpectralNearest::~SpectralNearest() = default;

void SpectralNearest::QueryBruteForce(const Eigen::MatrixXd& queries,
                                      std::vector<int>* rows) const {
  // Row-major single precision: one query's coordinates contiguous.
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> q =
      queries.cast<float>();
  NearestPacked(packed_, q.data(), static_cast<int>(q.rows()), rows->data());
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

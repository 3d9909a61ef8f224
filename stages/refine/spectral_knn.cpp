#include "stages/refine/spectral_knn.h"

#include <flann/flann.hpp>

#include "core/errors.h"

namespace symembed {

SpectralKdTree::SpectralKdTree(const Eigen::MatrixXd& points, std::vector<int> ids)
    : dims_(static_cast<int>(points.cols())), points_(points), ids_(std::move(ids)) {
  SYMEMBED_CHECK(points.rows() > 0 && points.cols() > 0, "kd-tree needs at least one point");
  SYMEMBED_CHECK(ids_.empty() || ids_.size() == static_cast<size_t>(points.rows()),
                 "kd-tree: " << ids_.size() << " ids for " << points.rows() << " points");
  flann::Matrix<double> data(points_.data(), points_.rows(), points_.cols());
  index_ = std::make_unique<flann::Index<flann::L2<double>>>(data,
                                                             flann::KDTreeSingleIndexParams(16));
  index_->buildIndex();
}

SpectralKdTree::~SpectralKdTree() = default;

void SpectralKdTree::Query(const Eigen::MatrixXd& queries, std::vector<int>* nearest,
                           std::vector<double>* sq_dist) const {
  SYMEMBED_CHECK(queries.cols() == dims_,
                 "kd-tree query has " << queries.cols() << " columns, tree " << dims_);
  SYMEMBED_CHECK(nearest != nullptr, "nearest is null");
  const int m = static_cast<int>(queries.rows());
  nearest->assign(m, -1);
  if (m == 0) {
    if (sq_dist != nullptr) sq_dist->clear();
    return;
  }
  RowMatrix q = queries;
  std::vector<double> dists(m);
  flann::Matrix<double> query_matrix(q.data(), m, dims_);
  flann::Matrix<int> index_matrix(nearest->data(), m, 1);
  flann::Matrix<double> dist_matrix(dists.data(), m, 1);
  // Exact search: the single kd-tree ignores `checks` and is exact with eps = 0.
  flann::SearchParams params(flann::FLANN_CHECKS_UNLIMITED, 0.0f);
  index_->knnSearch(query_matrix, index_matrix, dist_matrix, 1, params);
  if (!ids_.empty()) {
    for (int& i : *nearest) i = ids_[i];
  }
  if (sq_dist != nullptr) *sq_dist = std::move(dists);
}

}  // namespace symembed

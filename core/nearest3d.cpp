#include "core/nearest3d.h"

#include <algorithm>
#include <limits>
#include <numeric>
#include <string>

#include "core/errors.h"

namespace symembed {
namespace {
constexpr int kLeafSize = 8;
}  // namespace

Nearest3d::Nearest3d(const Eigen::MatrixX3d& points) {
  const int n = static_cast<int>(points.rows());
  if (n < 1) throw InvalidInputError("Nearest3d: empty point set");
  if (!points.allFinite()) throw InvalidInputError("Nearest3d: non-finite point coordinates");
  ids_.resize(n);
  std::iota(ids_.begin(), ids_.end(), 0);
  // Coordinates are read through ids_ while building, then stored in tree order.
  x_.assign(points.col(0).data(), points.col(0).data() + n);
  y_.assign(points.col(1).data(), points.col(1).data() + n);
  z_.assign(points.col(2).data(), points.col(2).data() + n);
  nodes_.reserve(2 * (n / kLeafSize + 1));
  Build(0, n);
  std::vector<double> x(n), y(n), z(n);
  for (int s = 0; s < n; ++s) {
    x[s] = x_[ids_[s]];
    y[s] = y_[ids_[s]];
    z[s] = z_[ids_[s]];
  }
  x_.swap(x);
  y_.swap(y);
  z_.swap(z);
  slots_.resize(n);
  for (int s = 0; s < n; ++s) slots_[ids_[s]] = s;
}

int Nearest3d::Build(int begin, int end) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{});
  nodes_[index].begin = begin;
  nodes_[index].end = end;
  if (end - begin <= kLeafSize) return index;
  const std::vector<double>* coords[3] = {&x_, &y_, &z_};
  int dim = 0;
  double widest = -1.0;
  for (int d = 0; d < 3; ++d) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int s = begin; s < end; ++s) {
      const double v = (*coords[d])[ids_[s]];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (hi - lo > widest) {
      widest = hi - lo;
      dim = d;
    }
  }
  const std::vector<double>& c = *coords[dim];
  const int mid = begin + (end - begin) / 2;
  std::nth_element(ids_.begin() + begin, ids_.begin() + mid, ids_.begin() + end,
                   [&](int a, int b) { return c[a] < c[b]; });
  const double split = c[ids_[mid]];
  const int left = Build(begin, mid);
  const int right = Build(mid, end);
  Node& node = nodes_[index];
  node.dim = dim;
  node.split = split;
  node.left = left;
  node.right = right;
  return index;
}

void Nearest3d::Search(int index, const double q[3], double off[3], double bound, double* best,
                       int* best_id) const {
  const Node& node = nodes_[index];
  if (node.dim < 0) {
    for (int s = node.begin; s < node.end; ++s) {
      const double dx = x_[s] - q[0], dy = y_[s] - q[1], dz = z_[s] - q[2];
      const double d = dx * dx + dy * dy + dz * dz;
      if (d < *best || (d == *best && ids_[s] < *best_id)) {
        *best = d;
        *best_id = ids_[s];
      }
    }
    return;
  }
  // Left holds coordinates <= split, right >= split: the nearer side first.
  const double diff = q[node.dim] - node.split;
  const int near = diff < 0.0 ? node.left : node.right;
  const int far = diff < 0.0 ? node.right : node.left;
  Search(near, q, off, bound, best, best_id);
  const double old = off[node.dim];
  const double far_bound = bound - old * old + diff * diff;
  // <=: a point as near as the best may still have a lower index.
  if (far_bound <= *best) {
    off[node.dim] = diff;
    Search(far, q, off, far_bound, best, best_id);
    off[node.dim] = old;
  }
}

int Nearest3d::Nearest(const double q[3], double* sq_dist, int hint) const {
  double off[3] = {0.0, 0.0, 0.0};
  double best = std::numeric_limits<double>::infinity();
  int best_id = std::numeric_limits<int>::max();
  if (hint >= 0 && hint < static_cast<int>(slots_.size())) {
    // The leaf scan's arithmetic, so the hint's distance is the one the scan would find.
    const int s = slots_[hint];
    const double dx = x_[s] - q[0], dy = y_[s] - q[1], dz = z_[s] - q[2];
    best = dx * dx + dy * dy + dz * dz;
    best_id = hint;
  }
  Search(0, q, off, 0.0, &best, &best_id);
  *sq_dist = best;
  return best_id;
}

}  // namespace symembed

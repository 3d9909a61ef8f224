#include "core/nearest_kd.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "core/errors.h"

namespace symembed {
namespace {
constexpr int kLeafSize = 8;
}  // namespace

template <int D>
NearestKd<D>::NearestKd(const double* points, int n) {
  if (n < 1) throw InvalidInputError("NearestKd: empty point set");
  for (long i = 0; i < static_cast<long>(n) * D; ++i) {
    if (!std::isfinite(points[i])) {
      throw InvalidInputError("NearestKd: non-finite coordinate of point " +
                              std::to_string(i / D));
    }
  }
  ids_.resize(n);
  std::iota(ids_.begin(), ids_.end(), 0);
  nodes_.reserve(2 * (n / kLeafSize + 1));
  Build(points, 0, n);
  coords_.resize(static_cast<size_t>(n) * D);
  slots_.resize(n);
  for (int s = 0; s < n; ++s) {
    std::copy_n(points + static_cast<size_t>(ids_[s]) * D, D, coords_.data() + static_cast<size_t>(s) * D);
    slots_[ids_[s]] = s;
  }
}

template <int D>
int NearestKd<D>::Build(const double* points, int begin, int end) {
  const int index = static_cast<int>(nodes_.size());
  nodes_.push_back(Node{});
  nodes_[index].begin = begin;
  nodes_[index].end = end;
  if (end - begin <= kLeafSize) return index;
  auto coord = [points](int id, int d) { return points[static_cast<size_t>(id) * D + d]; };
  int dim = 0;
  double widest = -1.0;
  for (int d = 0; d < D; ++d) {
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int s = begin; s < end; ++s) {
      const double v = coord(ids_[s], d);
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    if (hi - lo > widest) {
      widest = hi - lo;
      dim = d;
    }
  }
  const int mid = begin + (end - begin) / 2;
  std::nth_element(ids_.begin() + begin, ids_.begin() + mid, ids_.begin() + end,
                   [&](int a, int b) { return coord(a, dim) < coord(b, dim); });
  const double split = coord(ids_[mid], dim);
  const int left = Build(points, begin, mid);
  const int right = Build(points, mid, end);
  Node& node = nodes_[index];
  node.dim = dim;
  node.split = split;
  node.left = left;
  node.right = right;
  return index;
}

template <int D>
double NearestKd<D>::SquaredDistance(int slot, const double* q) const {
  const double* p = coords_.data() + static_cast<size_t>(slot) * D;
  // In coordinate order, a multiply then an add (nearest_kd.h).
  double d = 0.0;
  for (int c = 0; c < D; ++c) {
    const double diff = p[c] - q[c];
    d = d + diff * diff;
  }
  return d;
}

template <int D>
void NearestKd<D>::Search(int index, const double* q, double off[D], double bound, double* best,
                          int* best_id) const {
  const Node& node = nodes_[index];
  if (node.dim < 0) {
    for (int s = node.begin; s < node.end; ++s) {
      const double d = SquaredDistance(s, q);
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

template <int D>
int NearestKd<D>::Nearest(const double* q, double* sq_dist, int hint) const {
  double off[D] = {};
  double best = std::numeric_limits<double>::infinity();
  int best_id = std::numeric_limits<int>::max();
  if (hint >= 0 && hint < static_cast<int>(slots_.size())) {
    // The leaf scan's arithmetic, so the hint's distance is the one the scan would find.
    best = SquaredDistance(slots_[hint], q);
    best_id = hint;
  }
  Search(0, q, off, 0.0, &best, &best_id);
  *sq_dist = best;
  return best_id;
}

template class NearestKd<1>;
template class NearestKd<2>;
template class NearestKd<3>;
template class NearestKd<4>;
template class NearestKd<5>;
template class NearestKd<6>;
template class NearestKd<7>;

std::unique_ptr<NearestSearch> MakeNearestSearch(const double* points, int n, int dims) {
  switch (dims) {
    case 1: return std::make_unique<NearestKd<1>>(points, n);
    case 2: return std::make_unique<NearestKd<2>>(points, n);
    case 3: return std::make_unique<NearestKd<3>>(points, n);
    case 4: return std::make_unique<NearestKd<4>>(points, n);
    case 5: return std::make_unique<NearestKd<5>>(points, n);
    case 6: return std::make_unique<NearestKd<6>>(points, n);
    case 7: return std::make_unique<NearestKd<7>>(points, n);
    default:
      throw InvalidInputError("NearestKd: " + std::to_string(dims) +
                              " coordinates per point; 1 to " +
                              std::to_string(kMaxNearestKdDims) + " are supported");
  }
}

}  // namespace symembed

#include "core/nearest_kd.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "core/errors.h"

namespace symembed {
namespace {
constexpr int kLeafSize = 16;  // a multiple of 4

// The leaf scan keeps (best, best_id) the lowest (squared distance, index) pair seen: the order
// of the points does not matter, so a block of them may be measured at once and the lowest
// taken after. Each distance is (((p_0 - q_0)^2 + (p_1 - q_1)^2) + ...), a multiply then an
// add, in every build.
template <int D>
void ScanLeafBaseline(const double* coords, const int* ids, const double* q, double* best,
                      int* best_id) {
  for (int k = 0; k < kLeafSize; ++k) {
    double d = 0.0;
    for (int c = 0; c < D; ++c) {
      const double diff = coords[c * kLeafSize + k] - q[c];
      d = d + diff * diff;
    }
    if (d < *best || (d == *best && ids[k] < *best_id)) {
      *best = d;
      *best_id = ids[k];
    }
  }
}

template <int D>
__attribute__((target("avx2"))) void ScanLeafAvx2(const double* coords, const int* ids,
                                                  const double* q, double* best, int* best_id) {
  constexpr int kBlocks = kLeafSize / 4;
  __m256d d[kBlocks];
  for (int h = 0; h < kBlocks; ++h) {
    // 0 + x is x for the squares (never -0), so the first square starts the sum.
    __m256d diff = _mm256_sub_pd(_mm256_loadu_pd(coords + 4 * h), _mm256_set1_pd(q[0]));
    d[h] = _mm256_mul_pd(diff, diff);
    for (int c = 1; c < D; ++c) {
      diff = _mm256_sub_pd(_mm256_loadu_pd(coords + c * kLeafSize + 4 * h), _mm256_set1_pd(q[c]));
      d[h] = _mm256_add_pd(d[h], _mm256_mul_pd(diff, diff));
    }
  }
  __m256d m = d[0];
  for (int h = 1; h < kBlocks; ++h) m = _mm256_min_pd(m, d[h]);
  m = _mm256_min_pd(m, _mm256_permute4x64_pd(m, 0x4e));
  m = _mm256_min_pd(m, _mm256_permute_pd(m, 0x5));
  const double lowest = _mm256_cvtsd_f64(m);
  // Not "lowest > *best": a NaN distance (a NaN query) changes nothing, as in the baseline.
  if (!(lowest <= *best)) return;
  alignas(32) double values[kLeafSize];
  for (int h = 0; h < kBlocks; ++h) _mm256_store_pd(values + 4 * h, d[h]);
  int id = *best_id;
  if (lowest < *best) id = std::numeric_limits<int>::max();
  for (int k = 0; k < kLeafSize; ++k) {
    if (values[k] == lowest && ids[k] < id) id = ids[k];
  }
  *best = lowest;
  *best_id = id;
}

}  // namespace

template <int D>
NearestKd<D>::NearestKd(const double* points, int n, NearestIsa isa) {
  SYMEMBED_CHECK(NearestKernelSupports(isa), "NearestKd: a build this processor cannot run");
  avx2_ = isa != NearestIsa::kBaseline && NearestKernelSupports(NearestIsa::kAvx2);
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
  int leaves = 0;
  for (Node& node : nodes_) {
    if (node.dim < 0) node.leaf = leaves++;
  }
  leaf_coords_.assign(static_cast<size_t>(leaves) * D * kLeafSize,
                      std::numeric_limits<double>::infinity());
  leaf_ids_.assign(static_cast<size_t>(leaves) * kLeafSize, std::numeric_limits<int>::max());
  for (const Node& node : nodes_) {
    if (node.dim >= 0) continue;
    SYMEMBED_CHECK(node.end - node.begin <= kLeafSize, "a leaf of " << node.end - node.begin);
    for (int s = node.begin; s < node.end; ++s) {
      const int k = s - node.begin;
      leaf_ids_[static_cast<size_t>(node.leaf) * kLeafSize + k] = ids_[s];
      for (int c = 0; c < D; ++c) {
        leaf_coords_[(static_cast<size_t>(node.leaf) * D + c) * kLeafSize + k] =
            coords_[static_cast<size_t>(s) * D + c];
      }
    }
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
    const double* coords = leaf_coords_.data() + static_cast<size_t>(node.leaf) * D * kLeafSize;
    const int* ids = leaf_ids_.data() + static_cast<size_t>(node.leaf) * kLeafSize;
    if (avx2_) {
      ScanLeafAvx2<D>(coords, ids, q, best, best_id);
    } else {
      ScanLeafBaseline<D>(coords, ids, q, best, best_id);
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

std::unique_ptr<NearestSearch> MakeNearestSearch(const double* points, int n, int dims,
                                                 NearestIsa isa) {
  switch (dims) {
    case 1:
      return std::make_unique<NearestKd<1>>(points, n, isa);
    case 2:
      return std::make_unique<NearestKd<2>>(points, n, isa);
    case 3:
      return std::make_unique<NearestKd<3>>(points, n, isa);
    case 4:
      return std::make_unique<NearestKd<4>>(points, n, isa);
    case 5:
      return std::make_unique<NearestKd<5>>(points, n, isa);
    case 6:
      return std::make_unique<NearestKd<6>>(points, n, isa);
    case 7:
      return std::make_unique<NearestKd<7>>(points, n, isa);
    default:
      throw InvalidInputError("NearestKd: " + std::to_string(dims) +
                              " coordinates per point; 1 to " +
                              std::to_string(kMaxNearestKdDims) + " are supported");
  }
}

}  // namespace symembed

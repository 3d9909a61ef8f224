#include "core/sign_flip_nearest.h"

#include <flann/algorithms/dist.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "core/double_lanes.h"
#include "core/errors.h"
#include "core/nearest_kd.h"
#include "core/parallel.h"

namespace symembed {
namespace {

// Rows per block of the packed layout: one AVX-512 register of doubles.
constexpr int kFlipBlock = 8;

// The margin, relative to ||g_i||^2 + max_j ||g_j||^2, within which rows count as tied. The
// Gray-code values drift by at most a few hundred roundings of numbers of that size (about 1e-13
// relative), and the kd-tree's own distances differ from the exact ones by less still.
constexpr double kTieMargin = 1e-9;

// For one query row g (K coordinates): sweeps the patterns in Gray-code order and writes, per
// pattern s, the row of lowest c_j(s) to arg[s] and whether it is the only row within `margin`
// of it to unique[s]. packed: blocks x K x kFlipBlock coordinates (padding rows 0); norms:
// blocks x kFlipBlock squared norms (padding +inf); c: blocks x kFlipBlock scratch.
template <int kLanes>
__attribute__((always_inline)) inline void SweepKernel(const double* packed, const double* norms,
                                                       int blocks, int K, const double* g,
                                                       double margin, double* c, int* arg,
                                                       unsigned char* unique) {
  using Doubles = typename DoubleLanes<kLanes>::Doubles;
  using Bits = typename DoubleLanes<kLanes>::Bits;
  constexpr int kVectors = kFlipBlock / kLanes;
  const double inf = std::numeric_limits<double>::infinity();
  // c_j with no coordinate negated.
  for (int b = 0; b < blocks; ++b) {
    const double* block = packed + static_cast<long>(b) * K * kFlipBlock;
    for (int l = 0; l < kFlipBlock; ++l) {
      double dot = 0.0;
      for (int d = 0; d < K; ++d) dot += g[d] * block[d * kFlipBlock + l];
      c[b * kFlipBlock + l] = norms[b * kFlipBlock + l] - 2.0 * dot;
    }
  }
  double sign[12];
  for (int d = 0; d < K; ++d) sign[d] = 1.0;
  const unsigned count = 1u << K;
  for (unsigned t = 1; t < count; ++t) {
    const int d = __builtin_ctz(t);
    const unsigned pattern = t ^ (t >> 1);
    const double w = 4.0 * sign[d] * g[d];
    sign[d] = -sign[d];
    // Per lane, the lowest value, the row with it and the second lowest.
    Doubles low[kVectors], second[kVectors];
    Bits at[kVectors], index[kVectors];
    for (int v = 0; v < kVectors; ++v) {
      low[v] = Doubles{} + inf;
      second[v] = Doubles{} + inf;
      at[v] = Bits{};
      for (int l = 0; l < kLanes; ++l) index[v][l] = v * kLanes + l;
    }
    for (int b = 0; b < blocks; ++b) {
      const double* coords = packed + (static_cast<long>(b) * K + d) * kFlipBlock;
      double* cb = c + b * kFlipBlock;
      for (int v = 0; v < kVectors; ++v) {
        Doubles x;
        __builtin_memcpy(&x, cb + v * kLanes, sizeof(x));
        Doubles y;
        __builtin_memcpy(&y, coords + v * kLanes, sizeof(y));
        x = x + w * y;
        __builtin_memcpy(cb + v * kLanes, &x, sizeof(x));
        const Bits lower = x < low[v];
        const Doubles above = lower ? low[v] : x;
        second[v] = above < second[v] ? above : second[v];
        low[v] = lower ? x : low[v];
        at[v] = lower ? index[v] : at[v];
        index[v] = index[v] + kFlipBlock;
      }
    }
    double best = inf, next = inf;
    int row = 0;
    for (int v = 0; v < kVectors; ++v) {
      for (int l = 0; l < kLanes; ++l) {
        next = std::min(next, second[v][l]);
        if (low[v][l] < best) {
          next = std::min(next, best);
          best = low[v][l];
          row = static_cast<int>(at[v][l]);
        } else {
          next = std::min(next, low[v][l]);
        }
      }
    }
    arg[pattern] = row;
    unique[pattern] = next > best + margin;
  }
}

__attribute__((target("avx512f"))) void SweepAvx512(const double* packed, const double* norms,
                                                    int blocks, int K, const double* g,
                                                    double margin, double* c, int* arg,
                                                    unsigned char* unique) {
  SweepKernel<8>(packed, norms, blocks, K, g, margin, c, arg, unique);
}

__attribute__((target("avx2"))) void SweepAvx2(const double* packed, const double* norms,
                                               int blocks, int K, const double* g, double margin,
                                               double* c, int* arg, unsigned char* unique) {
  SweepKernel<4>(packed, norms, blocks, K, g, margin, c, arg, unique);
}

void SweepBaseline(const double* packed, const double* norms, int blocks, int K, const double* g,
                   double margin, double* c, int* arg, unsigned char* unique) {
  SweepKernel<2>(packed, norms, blocks, K, g, margin, c, arg, unique);
}

}  // namespace

SignFlipNeighbours NearestUnderSignFlips(const Eigen::MatrixXd& G, const KnnIndex& index,
                                         int threads, NearestIsa isa) {
  const int n = static_cast<int>(G.rows());
  const int K = static_cast<int>(G.cols());
  if (K < 1 || K > 12) {
    throw InvalidInputError("sign flips: " + std::to_string(K) + " coordinates (1 to 12)");
  }
  if (index.size() != n || index.dims() != K) {
    throw InvalidInputError("sign flips: the index holds " + std::to_string(index.size()) +
                            " points of " + std::to_string(index.dims()) + " coordinates for " +
                            std::to_string(n) + " x " + std::to_string(K));
  }
  SYMEMBED_CHECK(NearestKernelSupports(isa), "sign flips: a build this processor cannot run");
  SignFlipNeighbours out;
  out.rows = n;
  out.patterns = static_cast<int>((1u << K) - 1);
  out.nearest.assign(static_cast<size_t>(out.patterns) * n, 0);
  out.distances.assign(static_cast<size_t>(out.patterns) * n, 0.0);
  auto query = [&](unsigned pattern, const std::vector<int>& rows) {
    Eigen::MatrixXd Q(rows.size(), K);
    for (size_t r = 0; r < rows.size(); ++r) {
      for (int d = 0; d < K; ++d) Q(r, d) = (pattern >> d & 1u) ? -G(rows[r], d) : G(rows[r], d);
    }
    Eigen::VectorXd distances;
    const std::vector<int> nearest = index.Nearest(Q, &distances, 1);
    for (size_t r = 0; r < rows.size(); ++r) {
      const size_t at = static_cast<size_t>(pattern - 1) * n + rows[r];
      out.nearest[at] = nearest[r];
      out.distances[at] = distances(r);
    }
  };
  std::vector<int> all_rows(n);
  for (int i = 0; i < n; ++i) all_rows[i] = i;
  if (K <= kMaxNearestKdDims) {
    // KnnIndex answers these dimensions with its own kd-tree, whose arithmetic is its own; with
    // at most 127 patterns the queries themselves cost little.
    for (unsigned pattern = 1; pattern <= static_cast<unsigned>(out.patterns); ++pattern) {
      query(pattern, all_rows);
    }
    return out;
  }
  const int blocks = (n + kFlipBlock - 1) / kFlipBlock;
  std::vector<double> packed(static_cast<size_t>(blocks) * K * kFlipBlock, 0.0);
  std::vector<double> norms(static_cast<size_t>(blocks) * kFlipBlock,
                            std::numeric_limits<double>::infinity());
  std::vector<double> rows(G.size());  // row-major copy
  double max_norm = 0.0;
  for (int j = 0; j < n; ++j) {
    double sq = 0.0;
    for (int d = 0; d < K; ++d) {
      packed[(static_cast<size_t>(j / kFlipBlock) * K + d) * kFlipBlock + j % kFlipBlock] = G(j, d);
      rows[static_cast<size_t>(j) * K + d] = G(j, d);
      sq += G(j, d) * G(j, d);
    }
    norms[j] = sq;
    max_norm = std::max(max_norm, sq);
  }
  const NearestIsa build = ResolveNearestIsa(isa);
  auto sweep = build == NearestIsa::kAvx512 ? SweepAvx512
               : build == NearestIsa::kAvx2 ? SweepAvx2
                                            : SweepBaseline;
  // Per query row: the sweep's row and uniqueness for every pattern.
  std::vector<int> arg(static_cast<size_t>(n) << K);
  std::vector<unsigned char> unique(static_cast<size_t>(n) << K);
  constexpr int kRowsPerTask = 16;
  ParallelFor((n + kRowsPerTask - 1) / kRowsPerTask,
              [&](int task) {
                std::vector<double> c(static_cast<size_t>(blocks) * kFlipBlock);
                const int end = std::min(n, (task + 1) * kRowsPerTask);
                for (int i = task * kRowsPerTask; i < end; ++i) {
                  const double* g = rows.data() + static_cast<size_t>(i) * K;
                  const double margin = kTieMargin * (norms[i] + max_norm);
                  const size_t at = static_cast<size_t>(i) << K;
                  sweep(packed.data(), norms.data(), blocks, K, g, margin, c.data(),
                        arg.data() + at, unique.data() + at);
                }
              },
              threads);
  // The rows found alone get the kd-tree's distance; the ties go to the kd-tree.
  std::vector<int> tied;
  double q[12];
  for (unsigned pattern = 1; pattern <= static_cast<unsigned>(out.patterns); ++pattern) {
    tied.clear();
    for (int i = 0; i < n; ++i) {
      const size_t from = (static_cast<size_t>(i) << K) + pattern;
      if (!unique[from]) {
        tied.push_back(i);
        continue;
      }
      const int j = arg[from];
      for (int d = 0; d < K; ++d) q[d] = (pattern >> d & 1u) ? -G(i, d) : G(i, d);
      const size_t at = static_cast<size_t>(pattern - 1) * n + i;
      out.nearest[at] = j;
      // The kd-tree's own distance (FLANN's L2), computed here, outside the builds above, whose
      // fused multiply-adds would round differently.
      const double sq = flann::L2<double>()(q, rows.data() + static_cast<size_t>(j) * K, K);
      out.distances[at] = std::sqrt(std::max(0.0, sq));
    }
    if (!tied.empty()) query(pattern, tied);
  }
  return out;
}

}  // namespace symembed

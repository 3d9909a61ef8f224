#include "core/matching/l1_nearest.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <numeric>

#include "core/double_lanes.h"
#include "core/errors.h"

namespace symembed {
namespace {

// A block's partial sums are compared with the lowest full sum after this many rows: often
// enough that a far block stops early, rarely enough that the comparison costs little.
constexpr int kCheckRows = 4;

template <int kLanes>
__attribute__((always_inline)) inline std::pair<int, double> NearestKernel(
    const double* packed, int rows, int blocks, const double* x, const int* row_ids, int count) {
  using Doubles = typename DoubleLanes<kLanes>::Doubles;
  using Bits = typename DoubleLanes<kLanes>::Bits;
  using DoublesUnaligned = typename DoubleLanes<kLanes>::DoublesUnaligned;
  constexpr int kVectors = kL1Block / kLanes;
  static_assert(kL1Block % kLanes == 0, "a block is whole vectors");
  const double inf = std::numeric_limits<double>::infinity();
  // Clearing the sign bit is std::abs, bit for bit.
  const Bits magnitude = Bits{} + std::numeric_limits<int64_t>::max();
  // Per lane, the lowest full sum of the columns it has held and the first column with it; their
  // lowest is the lowest full sum of every column so far.
  Doubles best[kVectors];
  Bits arg[kVectors], index[kVectors];
  for (int v = 0; v < kVectors; ++v) {
    best[v] = Doubles{} + inf;
    arg[v] = Bits{};
    for (int l = 0; l < kLanes; ++l) index[v][l] = v * kLanes + l;
  }
  double lowest = inf;  // the lowest of `best`, kept up to date only where blocks stop early
  const bool checks = count > kCheckRows;
  for (int b = 0; b < blocks; ++b) {
    const double* block = packed + static_cast<long>(b) * rows * kL1Block;
    Doubles acc[kVectors];
    for (int v = 0; v < kVectors; ++v) acc[v] = Doubles{};  // +0, as the plain loop's sum
    bool beaten = false;
    for (int t = 0; t < count && !beaten;) {
      const int stop = std::min(count, t + kCheckRows);
      for (; t < stop; ++t) {
        const double* row = block + static_cast<long>(row_ids[t]) * kL1Block;
        const double xt = x[t];
        for (int v = 0; v < kVectors; ++v) {
          const Doubles d = *reinterpret_cast<const DoublesUnaligned*>(row + v * kLanes) - xt;
          acc[v] = acc[v] + reinterpret_cast<Doubles>(reinterpret_cast<Bits>(d) & magnitude);
        }
      }
      if (t == count) break;
      // Partial sums only grow: a column already at the lowest full sum cannot go below it, and
      // one equal to it comes later than the column that has it.
      beaten = true;
      for (int v = 0; v < kVectors && beaten; ++v) {
        for (int l = 0; l < kLanes; ++l) beaten = beaten && acc[v][l] >= lowest;
      }
    }
    if (!beaten) {
      // Strictly lower: within a lane the columns come in order, so the first lowest is kept.
      for (int v = 0; v < kVectors; ++v) {
        const Bits lower = acc[v] < best[v];
        best[v] = lower ? acc[v] : best[v];
        arg[v] = lower ? index[v] : arg[v];
      }
      if (checks) {
        for (int v = 0; v < kVectors; ++v) {
          for (int l = 0; l < kLanes; ++l) lowest = std::min(lowest, acc[v][l]);
        }
      }
    }
    for (int v = 0; v < kVectors; ++v) index[v] = index[v] + kL1Block;
  }
  double value = inf;
  int column = 0;
  for (int v = 0; v < kVectors; ++v) {
    for (int l = 0; l < kLanes; ++l) {
      const int at = static_cast<int>(arg[v][l]);
      if (best[v][l] < value || (best[v][l] == value && at < column)) {
        value = best[v][l];
        column = at;
      }
    }
  }
  return {column, value};
}

__attribute__((target("avx512f"))) std::pair<int, double> NearestAvx512(
    const double* packed, int rows, int blocks, const double* x, const int* row_ids, int count) {
  return NearestKernel<8>(packed, rows, blocks, x, row_ids, count);
}

__attribute__((target("avx2"))) std::pair<int, double> NearestAvx2(const double* packed, int rows,
                                                                   int blocks, const double* x,
                                                                   const int* row_ids, int count) {
  return NearestKernel<4>(packed, rows, blocks, x, row_ids, count);
}

std::pair<int, double> NearestBaseline(const double* packed, int rows, int blocks, const double* x,
                                       const int* row_ids, int count) {
  return NearestKernel<2>(packed, rows, blocks, x, row_ids, count);
}

}  // namespace

L1Columns::L1Columns(const Eigen::MatrixXd& m, NearestIsa isa)
    : rows_(static_cast<int>(m.rows())),
      cols_(static_cast<int>(m.cols())),
      blocks_((cols_ + kL1Block - 1) / kL1Block),
      packed_(static_cast<size_t>(blocks_) * rows_ * kL1Block,
              std::numeric_limits<double>::infinity()),
      all_rows_(rows_) {
  if (cols_ < 1) throw InvalidInputError("L1Columns: no columns");
  SYMEMBED_CHECK(NearestKernelSupports(isa),
                 "L1Columns: a build this processor cannot run was asked for");
  isa_ = ResolveNearestIsa(isa);
  std::iota(all_rows_.begin(), all_rows_.end(), 0);
  for (int j = 0; j < cols_; ++j) {
    double* out =
        packed_.data() + static_cast<size_t>(j / kL1Block) * rows_ * kL1Block + j % kL1Block;
    for (int i = 0; i < rows_; ++i) out[static_cast<size_t>(i) * kL1Block] = m(i, j);
  }
}

std::pair<int, double> L1Columns::Nearest(const double* x) const {
  return Nearest(x, all_rows_.data(), rows_);
}

std::pair<int, double> L1Columns::Nearest(const double* x, const int* row_ids, int count) const {
  switch (isa_) {
    case NearestIsa::kAvx512:
      return NearestAvx512(packed_.data(), rows_, blocks_, x, row_ids, count);
    case NearestIsa::kAvx2:
      return NearestAvx2(packed_.data(), rows_, blocks_, x, row_ids, count);
    default:
      return NearestBaseline(packed_.data(), rows_, blocks_, x, row_ids, count);
  }
}

}  // namespace symembed

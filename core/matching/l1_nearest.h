// Exact nearest column in L1: of the columns of a matrix (rows: distances to landmarks,
// columns: the vertices or samples they describe), the one whose entries differ least in sum of
// absolute differences from a query's, over all rows or over a chosen list of them.
//
// The columns are packed in blocks of kL1Block, each block stored row by row (the block's
// kL1Block entries of row 0, then of row 1, ...), so that one pass adds a row's differences for
// a whole block at once; a block stops being summed once each of its columns' partial sum has
// reached the lowest full sum so far. The arithmetic is fixed: a column's sum starts at 0 and adds
// |entry - query| row after row in the order given, so the sums, the column found (the lowest
// index among equal sums) and its sum are those of the plain loop over columns and rows, bit for
// bit, whichever of the three builds (AVX-512, AVX2, x86-64 baseline) the processor runs.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

#include "core/fmap/nearest_kernel.h"

namespace symembed {

constexpr int kL1Block = 8;

class L1Columns {
 public:
  // rows x cols, copied into the packed layout (padding columns hold +infinity). `isa`: the build
  // of the search to run, the widest the processor supports by default (another for tests and
  // benchmarks; NearestKernelSupports says which it runs; one it does not run is a programming
  // error, as for NearestPacked). Throws InvalidInputError for a matrix without columns.
  explicit L1Columns(const Eigen::MatrixXd& m, NearestIsa isa = NearestIsa::kAuto);

  // The column nearest to x (rows() entries) over every row in order, and its L1 distance.
  std::pair<int, double> Nearest(const double* x) const;
  // The same over the rows `row_ids` (count of them, each in [0, rows())) in that order, x[t]
  // the query's entry of row row_ids[t].
  std::pair<int, double> Nearest(const double* x, const int* row_ids, int count) const;

 private:
  int rows_ = 0;
  int cols_ = 0;
  int blocks_ = 0;
  NearestIsa isa_ = NearestIsa::kAuto;  // resolved: never kAuto
  std::vector<double> packed_;  // blocks x rows x kL1Block
  std::vector<int> all_rows_;   // 0, 1, ..., rows - 1
};

}  // namespace symembed

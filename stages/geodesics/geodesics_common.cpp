#include "stages/geodesics/geodesics_common.h"

#include <algorithm>

#include "core/errors.h"
#include "core/parallel.h"

namespace symembed {

bool GeodesicsCommonOptions::IsValid(std::string* error) const {
  if (threads < 0) {
    if (error) *error = "threads must be >= 0 (0 = all cores), got " + std::to_string(threads);
    return false;
  }
  return true;
}

Eigen::MatrixXd ParallelRows(const std::vector<int>& sources, int n, int threads,
                             const std::function<void(int, double*)>& row_fn) {
  for (int s : sources) {
    if (s < 0 || s >= n) {
      throw InvalidInputError("geodesic source " + std::to_string(s) +
                              " is not a vertex id in [0, " + std::to_string(n) + ")");
    }
  }
  const int m = static_cast<int>(sources.size());
  Eigen::MatrixXd D(m, n);
  // Rows are computed into a contiguous row-major buffer of kBlock sources and copied as a
  // block: D is column-major, so each column then receives kBlock adjacent values instead of
  // one strided write per source.
  constexpr int kBlock = 16;
  const int blocks = (m + kBlock - 1) / kBlock;
  ParallelFor(
      blocks,
      [&](int b) {
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        thread_local RowMajor buffer;
        const int begin = b * kBlock, count = std::min(kBlock, m - begin);
        buffer.resize(count, n);
        for (int i = 0; i < count; ++i) row_fn(begin + i, buffer.row(i).data());
        D.middleRows(begin, count) = buffer;
      },
      threads);
  return D;
}

}  // namespace symembed

#include "stages/geodesics/geodesics_common.h"

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

GeodesicsCommonOptions ReadGeodesicsCommonOptions(OptionReader& reader) {
  GeodesicsCommonOptions o;
  o.threads = reader.GetInt("threads", o.threads, 0, 1024);
  o.precision = reader.GetEnum<GeodesicPrecision>(
      "precision", o.precision,
      {{"double", GeodesicPrecision::kDouble}, {"float", GeodesicPrecision::kFloat}});
  return o;
}

Eigen::MatrixXd ParallelRows(const std::vector<int>& sources, int n, int threads,
                             const std::function<void(int, double*)>& row_fn) {
  for (int s : sources) {
    if (s < 0 || s >= n) {
      throw InvalidInputError("geodesic source " + std::to_string(s) + " is not a vertex id in [0, " +
                              std::to_string(n) + ")");
    }
  }
  const int m = static_cast<int>(sources.size());
  Eigen::MatrixXd D(m, n);
  // Rows are computed into a contiguous buffer and copied: D is column-major, and the solvers'
  // inner loops want unit stride.
  ParallelFor(
      m,
      [&](int i) {
        thread_local std::vector<double> row;
        row.resize(n);
        row_fn(i, row.data());
        D.row(i) = Eigen::Map<const Eigen::RowVectorXd>(row.data(), n);
      },
      threads);
  return D;
}

}  // namespace symembed

// Options and helpers shared by the geodesic solvers (dijkstra, fast_marching, heat).
#pragma once

#include <string>

#include "core/parallel.h"
#include "core/range.h"

namespace symembed {

// Scalar type of a solver's per-source working arrays. The output is always an Eigen::MatrixXd;
// kFloat halves the memory traffic of the inner loops (dijkstra, fast_marching) or of the
// per-source solves (heat) at the cost of about 7 significant digits.
enum class GeodesicPrecision { kDouble, kFloat };

struct GeodesicsCommonOptions {
  int threads = 0;                                           // worker threads, 0 = all cores
  static constexpr Range kThreads = Range::Closed(0, 1024);
  GeodesicPrecision precision = GeodesicPrecision::kDouble;  // internal accumulation

  bool IsValid(std::string* error) const;
};

}  // namespace symembed

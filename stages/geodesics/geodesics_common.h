// Options and helpers shared by the geodesic solvers (dijkstra, fast_marching, heat).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

namespace symembed {

// Scalar type of a solver's per-source working arrays. The output is always an Eigen::MatrixXd;
// kFloat halves the memory traffic of the inner loops (dijkstra, fast_marching) or of the
// per-source solves (heat) at the cost of about 7 significant digits.
enum class GeodesicPrecision { kDouble, kFloat };

struct GeodesicsCommonOptions {
  int threads = 0;                                           // worker threads, 0 = all cores
  GeodesicPrecision precision = GeodesicPrecision::kDouble;  // internal accumulation

  bool IsValid(std::string* error) const;
};

// Fills a #sources x n matrix in parallel over sources: row_fn(i, out) writes the n distances
// of source i to out (a contiguous per-thread buffer). Throws InvalidInputError for a source
// outside [0, n).
Eigen::MatrixXd ParallelRows(const std::vector<int>& sources, int n, int threads,
                             const std::function<void(int, double*)>& row_fn);

}  // namespace symembed

#include "stages/refine/nearest_kernel.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

namespace symembed {
namespace {

// The kernel's arithmetic written out one scalar at a time: ||p||^2 and q.p summed in dimension
// order, a multiply then an add; the first point with the lowest ||p||^2 - 2 q.p.
std::vector<int> ScalarNearest(const std::vector<float>& points, int n, int dims,
                               const std::vector<float>& queries, int m) {
  std::vector<int> out(m, 0);
  for (int r = 0; r < m; ++r) {
    float best = std::numeric_limits<float>::infinity();
    for (int i = 0; i < n; ++i) {
      float norm = 0.0f, dot = 0.0f;
      for (int c = 0; c < dims; ++c) {
        const float p = points[i + static_cast<size_t>(c) * n];
        norm = norm + p * p;
        dot = dot + queries[static_cast<size_t>(r) * dims + c] * p;
      }
      const float d = norm - 2.0f * dot;
      if (d < best) {
        best = d;
        out[r] = i;
      }
    }
  }
  return out;
}

std::vector<NearestIsa> AvailableIsas() {
  std::vector<NearestIsa> isas = {NearestIsa::kAuto, NearestIsa::kBaseline};
  if (NearestKernelHasAvx2()) isas.push_back(NearestIsa::kAvx2);
  return isas;
}

TEST(NearestKernel, EveryBuildMatchesTheScalarArithmeticExactly) {
  std::mt19937 rng(5);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  // Point counts off the block size and query counts off the tile size; one dimension and many.
  for (const auto& [n, dims, m] :
       std::vector<std::array<int, 3>>{{1, 1, 1}, {23, 3, 5}, {24, 7, 4}, {25, 20, 9},
                                       {97, 64, 31}, {500, 120, 7}}) {
    std::vector<float> points(static_cast<size_t>(n) * dims), queries(static_cast<size_t>(m) * dims);
    for (float& x : points) x = normal(rng);
    for (float& x : queries) x = normal(rng);
    const std::vector<int> expected = ScalarNearest(points, n, dims, queries, m);
    const PackedPoints packed = PackPoints(points.data(), n, dims, n);
    for (const NearestIsa isa : AvailableIsas()) {
      std::vector<int> nearest(m, -1);
      NearestPacked(packed, queries.data(), m, nearest.data(), isa);
      EXPECT_EQ(nearest, expected) << "n " << n << " dims " << dims << " isa "
                                   << static_cast<int>(isa);
    }
  }
}

TEST(NearestKernel, TiesGoToTheLowestIndexAcrossLanesAndBlocks) {
  // 60 points, 10 distinct ones repeated six times (index i is point i % 10): every query's
  // nearest value is attained at six indices in different lanes and blocks; the lowest is i % 10.
  const int n = 60, dims = 4, m = 10;
  std::vector<float> points(n * dims), queries(m * dims);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < dims; ++c) points[i + c * n] = static_cast<float>((i % 10) * (c + 1));
  }
  for (int r = 0; r < m; ++r) {
    for (int c = 0; c < dims; ++c) queries[r * dims + c] = points[r + c * n];
  }
  const PackedPoints packed = PackPoints(points.data(), n, dims, n);
  for (const NearestIsa isa : AvailableIsas()) {
    std::vector<int> nearest(m, -1);
    NearestPacked(packed, queries.data(), m, nearest.data(), isa);
    for (int r = 0; r < m; ++r) EXPECT_EQ(nearest[r], r) << static_cast<int>(isa);
  }
}

TEST(NearestKernel, StrideSkipsRowsAndNanQueriesGetZero) {
  // A 3 x 2 block of a 5-row column-major matrix: rows 3 and 4 are not points.
  const std::vector<float> matrix = {0, 10, 20, -1, -1, 0, 10, 20, -1, -1};
  const PackedPoints packed = PackPoints(matrix.data(), 3, 2, 5);
  EXPECT_EQ(packed.count, 3);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const std::vector<float> queries = {19, 21, 11, 9, nan, nan, -1, -1};
  std::vector<int> nearest(4, -1);
  NearestPacked(packed, queries.data(), 4, nearest.data());
  EXPECT_EQ(nearest, (std::vector<int>{2, 1, 0, 0}));
}

TEST(NearestKernel, RejectsEmptyPointSets) {
  const std::vector<float> none;
  EXPECT_ANY_THROW(PackPoints(none.data(), 0, 3, 0));
  EXPECT_ANY_THROW(PackPoints(none.data(), 4, 3, 2));
}

}  // namespace
}  // namespace symembed

#include "core/fmap/nearest_kernel.h"

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
  for (const NearestIsa isa : {NearestIsa::kAvx2, NearestIsa::kAvx512}) {
    if (NearestKernelSupports(isa)) isas.push_back(isa);
  }
  return isas;
}

TEST(NearestKernel, EveryBuildMatchesTheScalarArithmeticExactly) {
  std::mt19937 rng(5);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  // Point counts off the block (48) and its parts (24 and 48 points), query counts off the tiles
  // (2, 4 and 8 queries); one dimension and many.
  for (const auto& [n, dims, m] :
       std::vector<std::array<int, 3>>{{1, 1, 1}, {23, 3, 5}, {24, 7, 4}, {25, 20, 9},
                                       {47, 5, 8}, {48, 11, 17}, {49, 2, 3},
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

TEST(NearestKernel, NearTiesDecidedByRoundingMatchTheScalarArithmetic) {
  // Every point lies on a sphere around the query, so the values ||p||^2 - 2 q.p differ only by
  // rounding and the nearest point is decided by it: a build that fused a multiply and an add,
  // or summed in another order, picks other points for many of the queries.
  std::mt19937 rng(11);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  const int n = 200, dims = 16, m = 64;
  std::vector<float> queries(static_cast<size_t>(m) * dims);
  for (float& x : queries) x = normal(rng);
  for (int r = 0; r < m; ++r) {
    std::vector<float> points(static_cast<size_t>(n) * dims);
    for (int i = 0; i < n; ++i) {
      std::vector<double> u(dims);
      double norm = 0.0;
      for (double& x : u) {
        x = normal(rng);
        norm += x * x;
      }
      for (int c = 0; c < dims; ++c) {
        points[i + static_cast<size_t>(c) * n] =
            static_cast<float>(queries[static_cast<size_t>(r) * dims + c] + 3.0 * u[c] / std::sqrt(norm));
      }
    }
    const std::vector<float> query(queries.begin() + static_cast<long>(r) * dims,
                                   queries.begin() + static_cast<long>(r + 1) * dims);
    const std::vector<int> expected = ScalarNearest(points, n, dims, query, 1);
    const PackedPoints packed = PackPoints(points.data(), n, dims, n);
    for (const NearestIsa isa : AvailableIsas()) {
      int nearest = -1;
      NearestPacked(packed, query.data(), 1, &nearest, isa);
      EXPECT_EQ(nearest, expected[0]) << "query " << r << " isa " << static_cast<int>(isa);
    }
  }
}

TEST(NearestKernel, TiesGoToTheLowestIndexAcrossLanesAndBlocks) {
  // 130 points, 10 distinct ones repeated 13 times (index i is point i % 10): every query's
  // nearest value is attained at 13 indices in different lanes, parts of blocks and blocks; the
  // lowest is i % 10.
  const int n = 130, dims = 4, m = 10;
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

TEST(NearestKernel, PacksWholeBlocks) {
  const std::vector<float> points(49 * 2, 1.0f);
  const PackedPoints packed = PackPoints(points.data(), 49, 2, 49);
  EXPECT_EQ(packed.sq_norms.size(), 2u * kNearestBlock);
  EXPECT_EQ(packed.coords.size(), 2u * 2 * kNearestBlock);
}

TEST(NearestKernel, RejectsEmptyPointSets) {
  const std::vector<float> none;
  EXPECT_ANY_THROW(PackPoints(none.data(), 0, 3, 0));
  EXPECT_ANY_THROW(PackPoints(none.data(), 4, 3, 2));
}

}  // namespace
}  // namespace symembed

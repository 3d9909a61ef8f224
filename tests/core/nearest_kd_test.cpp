#include "core/nearest_kd.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/errors.h"
#include "core/knn.h"

namespace symembed {
namespace {

using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The nearest point by scanning all of them, the lowest index among equally near ones.
int ScanNearest(const RowMajor& points, const double* q, double* sq) {
  int best_id = 0;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < points.rows(); ++i) {
    double d = 0.0;
    for (int c = 0; c < points.cols(); ++c) {
      const double diff = points(i, c) - q[c];
      d = d + diff * diff;
    }
    if (d < best) {
      best = d;
      best_id = i;
    }
  }
  *sq = best;
  return best_id;
}

// Points on a bumpy sphere in `dims` dimensions (a surface, as the pipeline searches; on a line,
// where a sphere is two points, normally distributed), and queries on it, inside it and far
// outside it.
void SurfaceAndQueries(int dims, RowMajor* points, RowMajor* queries) {
  std::mt19937 rng(3 + dims);
  std::normal_distribution<double> normal(0.0, 1.0);
  points->resize(2000, dims);
  queries->resize(600, dims);
  for (int i = 0; i < points->rows(); ++i) {
    for (int c = 0; c < dims; ++c) (*points)(i, c) = normal(rng);
    if (dims == 1) continue;
    const double r = points->row(i).norm();
    points->row(i) *= (1.0 + 0.1 * std::sin(5.0 * (*points)(i, 0) / r)) / r;
  }
  for (int r = 0; r < queries->rows(); ++r) {
    const double scale = r < 200 ? 1.0 : r < 400 ? 0.3 : 4.0;
    queries->row(r) = scale * points->row((r * 7) % points->rows());
    for (int c = 0; c < dims; ++c) (*queries)(r, c) += 0.05 * normal(rng);
  }
}

class NearestKdDims : public testing::TestWithParam<int> {};

TEST_P(NearestKdDims, MatchesAScanAndFlannOnASurfaceAndOnQueriesAwayFromIt) {
  const int dims = GetParam();
  RowMajor points, queries;
  SurfaceAndQueries(dims, &points, &queries);
  const auto index = MakeNearestSearch(points.data(), static_cast<int>(points.rows()), dims);
  ASSERT_EQ(index->dims(), dims);
  std::vector<int> nearest(queries.rows());
  Eigen::VectorXd sq(queries.rows());
  for (int r = 0; r < queries.rows(); ++r) {
    const double* q = queries.row(r).data();
    double scan_sq = 0.0;
    nearest[r] = index->Nearest(q, &sq(r));
    EXPECT_EQ(nearest[r], ScanNearest(points, q, &scan_sq)) << "query " << r;
    EXPECT_EQ(sq(r), scan_sq) << "query " << r;
    // A hint changes nothing: the previous answer, a point anywhere, the answer itself, none.
    for (const int hint : {r > 0 ? nearest[r - 1] : 0, (r * 131) % 2000, nearest[r], -1}) {
      double hinted_sq = 0.0;
      EXPECT_EQ(index->Nearest(q, &hinted_sq, hint), nearest[r]) << "query " << r << " hint " << hint;
      EXPECT_EQ(hinted_sq, sq(r)) << "query " << r << " hint " << hint;
    }
  }
  // KnnIndex::Nearest, which runs the tree, gives the same points and distances; FLANN's
  // kd-tree (KnnIndex::Query) too, bit for bit: the nearest points are unique here.
  const KnnIndex knn(points);
  Eigen::VectorXd dist;
  EXPECT_EQ(knn.Nearest(queries, &dist), nearest);
  Eigen::MatrixXi flann_ids;
  Eigen::MatrixXd flann_dist;
  knn.Query(queries, 1, &flann_ids, &flann_dist, 1);
  for (int r = 0; r < queries.rows(); ++r) {
    EXPECT_EQ(dist(r), std::sqrt(sq(r))) << "query " << r;
    EXPECT_EQ(flann_ids(r, 0), nearest[r]) << "query " << r;
    EXPECT_EQ(flann_dist(r, 0), dist(r)) << "query " << r;
  }
}

TEST_P(NearestKdDims, EveryBuildOfTheLeafScanGivesTheSameAnswersAndDistances) {
  if (!NearestKernelSupports(NearestIsa::kAvx2)) GTEST_SKIP() << "no AVX2 on this processor";
  const int dims = GetParam();
  RowMajor points, queries;
  SurfaceAndQueries(dims, &points, &queries);
  const int n = static_cast<int>(points.rows());
  const auto baseline = MakeNearestSearch(points.data(), n, dims, NearestIsa::kBaseline);
  const auto avx2 = MakeNearestSearch(points.data(), n, dims, NearestIsa::kAvx2);
  // The points themselves too: each query at distance 0 from one point.
  for (const RowMajor* set : {&queries, &points}) {
    for (int r = 0; r < set->rows(); ++r) {
      const double* q = set->row(r).data();
      double sq_base = 0.0, sq_avx2 = 0.0;
      EXPECT_EQ(baseline->Nearest(q, &sq_base), avx2->Nearest(q, &sq_avx2)) << "query " << r;
      EXPECT_EQ(sq_base, sq_avx2) << "query " << r;
    }
  }
  // A query with a NaN coordinate: the same answer and the same distance bits.
  std::vector<double> nan_query(dims, 0.5);
  nan_query[0] = std::numeric_limits<double>::quiet_NaN();
  double sq_base = 0.0, sq_avx2 = 0.0;
  EXPECT_EQ(baseline->Nearest(nan_query.data(), &sq_base),
            avx2->Nearest(nan_query.data(), &sq_avx2));
  EXPECT_EQ(std::memcmp(&sq_base, &sq_avx2, sizeof(double)), 0) << sq_base << " vs " << sq_avx2;
}

INSTANTIATE_TEST_SUITE_P(SeveralDims, NearestKdDims, testing::Values(1, 2, 3, 4, 5, 6, 7));

TEST(NearestKd, EquallyNearPointsGoToTheLowestIndex) {
  // A grid of 5 x 5 x 5 points, each present three times (indices i, i + 125, i + 250) and
  // queries at the grid points and halfway between neighbours (two or more equally near).
  RowMajor points(375, 3);
  for (int copy = 0; copy < 3; ++copy) {
    for (int i = 0; i < 125; ++i) {
      points.row(copy * 125 + (copy == 1 ? 124 - i : i)) << i % 5, (i / 5) % 5, i / 25;
    }
  }
  RowMajor queries(250, 3);
  for (int i = 0; i < 125; ++i) {
    queries.row(i) = points.row(i);
    queries.row(125 + i) = points.row(i) + Eigen::RowVector3d(0.5, 0.5, 0.0);
  }
  for (const NearestIsa isa : {NearestIsa::kBaseline, NearestIsa::kAvx2}) {
    if (!NearestKernelSupports(isa)) continue;
    const NearestKd<3> index(points.data(), 375, isa);
    for (int r = 0; r < queries.rows(); ++r) {
      const double* q = queries.row(r).data();
      double sq = 0.0, scan_sq = 0.0;
      const int nearest = index.Nearest(q, &sq);
      EXPECT_EQ(nearest, ScanNearest(points, q, &scan_sq)) << "query " << r;
      EXPECT_EQ(sq, scan_sq) << "query " << r;
      EXPECT_LT(nearest, 125) << "query " << r;
      // Hinted with an equally near copy of a higher index, the lowest index still wins.
      for (const int hint : {nearest + 125, nearest + 250}) {
        EXPECT_EQ(index.Nearest(q, &sq, hint), nearest) << "query " << r << " hint " << hint;
      }
    }
  }
}

TEST(NearestKd, BeyondSevenDimensionsKnnIndexFallsBackToFlann) {
  RowMajor points, queries;
  SurfaceAndQueries(9, &points, &queries);
  EXPECT_THROW(MakeNearestSearch(points.data(), static_cast<int>(points.rows()), 9),
               InvalidInputError);
  const std::vector<int> nearest = KnnIndex(points).Nearest(queries);
  for (int r = 0; r < queries.rows(); ++r) {
    double sq = 0.0;
    EXPECT_EQ(nearest[r], ScanNearest(points, queries.row(r).data(), &sq)) << "query " << r;
  }
}

TEST(NearestKd, RejectsEmptyAndNonFinitePoints) {
  const double none[1] = {0.0};
  EXPECT_THROW(NearestKd<3>(none, 0), InvalidInputError);
  RowMajor bad = RowMajor::Zero(4, 3);
  bad(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((NearestKd<3>(bad.data(), 4)), InvalidInputError);
}

}  // namespace
}  // namespace symembed

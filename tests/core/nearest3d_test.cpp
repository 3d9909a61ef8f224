#include "core/nearest3d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "core/errors.h"
#include "core/knn.h"

namespace symembed {
namespace {

// The nearest point by scanning all of them, the lowest index among equally near ones.
int ScanNearest(const Eigen::MatrixX3d& points, const Eigen::RowVector3d& q, double* sq) {
  int best_id = 0;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < points.rows(); ++i) {
    const double dx = points(i, 0) - q(0), dy = points(i, 1) - q(1), dz = points(i, 2) - q(2);
    const double d = dx * dx + dy * dy + dz * dz;
    if (d < best) {
      best = d;
      best_id = i;
    }
  }
  *sq = best;
  return best_id;
}

TEST(Nearest3d, MatchesAScanOnASurfaceAndOnQueriesAwayFromIt) {
  // Points on a bumpy sphere (a surface, as the flip scorers search), queries on it, inside it
  // and far outside it.
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixX3d points(2000, 3), queries(600, 3);
  for (int i = 0; i < points.rows(); ++i) {
    Eigen::RowVector3d p(normal(rng), normal(rng), normal(rng));
    p *= (1.0 + 0.1 * std::sin(5.0 * p(0) / p.norm())) / p.norm();
    points.row(i) = p;
  }
  for (int r = 0; r < queries.rows(); ++r) {
    const double scale = r < 200 ? 1.0 : r < 400 ? 0.3 : 4.0;
    queries.row(r) = scale * points.row((r * 7) % points.rows());
    queries.row(r) += 0.05 * Eigen::RowVector3d(normal(rng), normal(rng), normal(rng));
  }
  const Nearest3d index(points);
  std::vector<int> nearest(queries.rows());
  for (int r = 0; r < queries.rows(); ++r) {
    const double q[3] = {queries(r, 0), queries(r, 1), queries(r, 2)};
    double sq = 0.0, scan_sq = 0.0;
    nearest[r] = index.Nearest(q, &sq);
    EXPECT_EQ(nearest[r], ScanNearest(points, queries.row(r), &scan_sq)) << "query " << r;
    EXPECT_EQ(sq, scan_sq) << "query " << r;
    // A hint changes nothing: the previous answer, a point anywhere, the answer itself, none.
    for (const int hint : {r > 0 ? nearest[r - 1] : 0, (r * 131) % 2000, nearest[r], -1}) {
      double hinted_sq = 0.0;
      EXPECT_EQ(index.Nearest(q, &hinted_sq, hint), nearest[r]) << "query " << r << " hint " << hint;
      EXPECT_EQ(hinted_sq, sq) << "query " << r << " hint " << hint;
    }
  }
  // KnnIndex::Nearest, which runs it in 3D, gives the same points.
  EXPECT_EQ(KnnIndex(points).Nearest(queries), nearest);
}

TEST(Nearest3d, EquallyNearPointsGoToTheLowestIndex) {
  // A grid of 5 x 5 x 5 points, each present three times (indices i, i + 125, i + 250) and
  // queries at the grid points and halfway between neighbours (two or more equally near).
  Eigen::MatrixX3d points(375, 3);
  for (int copy = 0; copy < 3; ++copy) {
    for (int i = 0; i < 125; ++i) {
      points.row(copy * 125 + (copy == 1 ? 124 - i : i)) << i % 5, (i / 5) % 5, i / 25;
    }
  }
  Eigen::MatrixX3d queries(250, 3);
  for (int i = 0; i < 125; ++i) {
    queries.row(i) = points.row(i);
    queries.row(125 + i) = points.row(i) + Eigen::RowVector3d(0.5, 0.5, 0.0);
  }
  const Nearest3d index(points);
  for (int r = 0; r < queries.rows(); ++r) {
    const double q[3] = {queries(r, 0), queries(r, 1), queries(r, 2)};
    double sq = 0.0, scan_sq = 0.0;
    const int nearest = index.Nearest(q, &sq);
    EXPECT_EQ(nearest, ScanNearest(points, queries.row(r), &scan_sq)) << "query " << r;
    EXPECT_LT(nearest, 125) << "query " << r;
    // Hinted with an equally near copy of a higher index, the lowest index still wins.
    for (const int hint : {nearest + 125, nearest + 250}) {
      EXPECT_EQ(index.Nearest(q, &sq, hint), nearest) << "query " << r << " hint " << hint;
    }
  }
}

TEST(Nearest3d, RejectsEmptyAndNonFinitePoints) {
  EXPECT_THROW(Nearest3d(Eigen::MatrixX3d(0, 3)), InvalidInputError);
  Eigen::MatrixX3d bad = Eigen::MatrixX3d::Zero(4, 3);
  bad(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(Nearest3d{bad}, InvalidInputError);
}

}  // namespace
}  // namespace symembed

#include "core/knn.h"

#include <gtest/gtest.h>

#include <random>

#include "core/errors.h"

namespace symembed {
namespace {

Eigen::MatrixXd RandomPoints(int n, int d, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd P(n, d);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < d; ++c) P(i, c) = u(rng);
  }
  return P;
}

class KnnIndexDims : public ::testing::TestWithParam<int> {};

TEST_P(KnnIndexDims, MatchesBruteForce) {
  const int d = GetParam();
  const Eigen::MatrixXd P = RandomPoints(2000, d, 1), Q = RandomPoints(700, d, 2);
  const KnnIndex index(P);
  Eigen::MatrixXi nn;
  Eigen::MatrixXd dist;
  index.Query(Q, 5, &nn, &dist, 2);
  for (int q = 0; q < Q.rows(); ++q) {
    Eigen::VectorXd all = (P.rowwise() - Q.row(q)).rowwise().norm();
    std::vector<double> sorted(all.data(), all.data() + all.size());
    std::sort(sorted.begin(), sorted.end());
    for (int j = 0; j < 5; ++j) {
      // The kd-tree is exact: same distances as brute force up to rounding.
      EXPECT_NEAR(dist(q, j), sorted[j], 1e-12);
      EXPECT_NEAR(all(nn(q, j)), sorted[j], 1e-12);
    }
  }
  // Nearest (in 3D its own tree, Nearest3d) gives Query's first neighbour, on one thread or
  // several: random points have no equally near pairs.
  for (const int threads : {1, 2}) {
    Eigen::VectorXd nearest_dist;
    const std::vector<int> nearest = index.Nearest(Q, &nearest_dist, threads);
    ASSERT_EQ(nearest.size(), static_cast<size_t>(Q.rows()));
    for (int q = 0; q < Q.rows(); ++q) {
      EXPECT_EQ(nearest[q], nn(q, 0)) << "query " << q;
      EXPECT_EQ(nearest_dist(q), dist(q, 0)) << "query " << q;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(TwoAndThree, KnnIndexDims, ::testing::Values(2, 3));

TEST(KnnIndex, NearestOfItselfIsItself) {
  const Eigen::MatrixXd P = RandomPoints(500, 3, 3);
  Eigen::VectorXd dist;
  const std::vector<int> nn = KnnIndex(P).Nearest(P, &dist);
  for (int i = 0; i < 500; ++i) EXPECT_EQ(nn[i], i);
  EXPECT_EQ(dist.maxCoeff(), 0.0);
}

TEST(KnnIndex, NearestIn3dGivesEquallyNearPointsToTheLowestIndex) {
  // Every point twice (i and i + 64): each query's nearest distance is attained at both.
  Eigen::MatrixXd P(128, 3);
  for (int i = 0; i < 64; ++i) {
    P.row(i) << i % 4, (i / 4) % 4, i / 16;
    P.row(64 + i) = P.row(i);
  }
  const Eigen::MatrixXd Q = P.bottomRows(64).rowwise() + Eigen::RowVector3d(0.1, 0.2, 0.3);
  const std::vector<int> nearest = KnnIndex(P).Nearest(Q);
  for (int q = 0; q < 64; ++q) EXPECT_EQ(nearest[q], q);
}

TEST(KnnIndex, RejectsEmptyAndNonFinite) {
  EXPECT_THROW(KnnIndex(Eigen::MatrixXd(0, 3)), InvalidInputError);
  Eigen::MatrixXd P = RandomPoints(10, 3, 4);
  P(3, 1) = std::nan("");
  EXPECT_THROW(KnnIndex{P}, InvalidInputError);
}

}  // namespace
}  // namespace symembed

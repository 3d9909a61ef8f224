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
  // Nearest (its own tree, NearestKd) gives Query's first neighbour, on one thread or several:
  // random points have no equally near pairs.
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

TEST(KnnIndex, NearestGivesEquallyNearPointsToTheLowestIndex) {
  // Every point twice (i and i + 64): each query's nearest distance is attained at both.
  for (const int dims : {2, 3, 6}) {
    Eigen::MatrixXd P = Eigen::MatrixXd::Zero(128, dims);
    for (int i = 0; i < 64; ++i) {
      // Distinct grid points: 8 x 8 in 2D, 4 x 4 x 4 in the first three coordinates otherwise.
      const int base = dims == 2 ? 8 : 4;
      for (int c = 0; c < dims; ++c) {
        P(i, c) = (c % 3 == 0 ? i : c % 3 == 1 ? i / base : i / (base * base)) % base + c / 3;
      }
      P.row(64 + i) = P.row(i);
    }
    Eigen::MatrixXd Q = P.bottomRows(64);
    for (int c = 0; c < dims; ++c) Q.col(c).array() += 0.05 * (c + 1);
    const std::vector<int> nearest = KnnIndex(P).Nearest(Q);
    for (int q = 0; q < 64; ++q) EXPECT_EQ(nearest[q], q) << dims << "D, query " << q;
  }
}

TEST(KnnIndex, RejectsEmptyAndNonFinite) {
  EXPECT_THROW(KnnIndex(Eigen::MatrixXd(0, 3)), InvalidInputError);
  Eigen::MatrixXd P = RandomPoints(10, 3, 4);
  P(3, 1) = std::nan("");
  EXPECT_THROW(KnnIndex{P}, InvalidInputError);
}

}  // namespace
}  // namespace symembed

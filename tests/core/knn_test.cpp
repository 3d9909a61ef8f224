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
}

INSTANTIATE_TEST_SUITE_P(TwoAndThree, KnnIndexDims, ::testing::Values(2, 3));

TEST(KnnIndex, NearestOfItselfIsItself) {
  const Eigen::MatrixXd P = RandomPoints(500, 3, 3);
  Eigen::VectorXd dist;
  const std::vector<int> nn = KnnIndex(P).Nearest(P, &dist);
  for (int i = 0; i < 500; ++i) EXPECT_EQ(nn[i], i);
  EXPECT_EQ(dist.maxCoeff(), 0.0);
}

TEST(KnnIndex, RejectsEmptyAndNonFinite) {
  EXPECT_THROW(KnnIndex(Eigen::MatrixXd(0, 3)), InvalidInputError);
  Eigen::MatrixXd P = RandomPoints(10, 3, 4);
  P(3, 1) = std::nan("");
  EXPECT_THROW(KnnIndex{P}, InvalidInputError);
}

}  // namespace
}  // namespace symembed

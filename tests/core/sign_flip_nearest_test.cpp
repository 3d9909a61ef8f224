#include "core/sign_flip_nearest.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/errors.h"

namespace symembed {
namespace {

// KnnIndex::Nearest of every row with the pattern's coordinates negated, pattern by pattern.
SignFlipNeighbours PatternByPattern(const Eigen::MatrixXd& G) {
  const KnnIndex index(G);
  const int n = static_cast<int>(G.rows()), K = static_cast<int>(G.cols());
  SignFlipNeighbours out;
  out.rows = n;
  out.patterns = (1 << K) - 1;
  for (unsigned pattern = 1; pattern < (1u << K); ++pattern) {
    Eigen::MatrixXd Q = G;
    for (int d = 0; d < K; ++d) {
      if (pattern >> d & 1u) Q.col(d) = -Q.col(d);
    }
    Eigen::VectorXd distances;
    const std::vector<int> nearest = index.Nearest(Q, &distances, 1);
    out.nearest.insert(out.nearest.end(), nearest.begin(), nearest.end());
    out.distances.insert(out.distances.end(), distances.data(), distances.data() + n);
  }
  return out;
}

// Smooth coordinates (as eigenfunctions) or a coarse grid of values, where many rows lie equally
// near a flipped row and some rows repeat: the ties the sweep leaves to the kd-tree.
Eigen::MatrixXd Coordinates(int n, int K, bool grid, std::mt19937* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_int_distribution<int> cell(-2, 2);
  Eigen::MatrixXd G(n, K);
  for (int i = 0; i < n; ++i) {
    for (int d = 0; d < K; ++d) G(i, d) = grid ? 0.25 * cell(*rng) : normal(*rng) / (1.0 + d);
  }
  return G;
}

class SignFlipNearestIsa : public testing::TestWithParam<NearestIsa> {};

// Every build the processor runs (the others are skipped).
TEST_P(SignFlipNearestIsa, FindsTheKdTreesRowsAndDistancesBitForBit) {
  if (!NearestKernelSupports(GetParam())) GTEST_SKIP() << "this processor lacks that build";
  std::mt19937 rng(11);
  for (const int K : {3, 8, 9, 12}) {
    for (const bool grid : {false, true}) {
      const int n = K == 12 ? 61 : 203;
      const Eigen::MatrixXd G = Coordinates(n, K, grid, &rng);
      const KnnIndex index(G);
      const SignFlipNeighbours expected = PatternByPattern(G);
      for (const int threads : {1, 2}) {
        const SignFlipNeighbours found = NearestUnderSignFlips(G, index, threads, GetParam());
        EXPECT_EQ(found.rows, n);
        EXPECT_EQ(found.patterns, expected.patterns);
        EXPECT_EQ(found.nearest, expected.nearest) << "K " << K << " grid " << grid;
        EXPECT_EQ(found.distances, expected.distances) << "K " << K << " grid " << grid;
      }
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Builds, SignFlipNearestIsa,
                         testing::Values(NearestIsa::kAuto, NearestIsa::kAvx512, NearestIsa::kAvx2,
                                         NearestIsa::kBaseline));

TEST(SignFlipNearest, AnIndexOfOtherPointsIsAnError) {
  std::mt19937 rng(3);
  const Eigen::MatrixXd G = Coordinates(20, 8, false, &rng);
  const KnnIndex fewer(G.topRows(19));
  EXPECT_THROW(NearestUnderSignFlips(G, fewer), InvalidInputError);
  const Eigen::MatrixXd wide = Coordinates(20, 13, false, &rng);
  EXPECT_THROW(NearestUnderSignFlips(wide, KnnIndex(wide)), InvalidInputError);
}

}  // namespace
}  // namespace symembed

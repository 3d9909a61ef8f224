#include "core/matching/l1_nearest.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "core/errors.h"

namespace symembed {
namespace {

// The plain loop over columns, each sum over the rows in order and left as soon as it reaches
// the lowest so far: the lowest index among equal sums.
std::pair<int, double> PlainNearest(const Eigen::MatrixXd& m, const std::vector<double>& x,
                                    const std::vector<int>& rows) {
  int best = 0;
  double best_cost = std::numeric_limits<double>::infinity();
  for (int j = 0; j < m.cols(); ++j) {
    double cost = 0.0;
    for (size_t t = 0; t < rows.size() && cost < best_cost; ++t) {
      cost += std::abs(m(rows[t], j) - x[t]);
    }
    if (cost < best_cost) {
      best_cost = cost;
      best = j;
    }
  }
  return {best, best_cost};
}

// Entries on a coarse grid, so that many columns tie, and some infinite (unreached vertices).
Eigen::MatrixXd GridMatrix(int rows, int cols, std::mt19937* rng) {
  std::uniform_int_distribution<int> cell(0, 6);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::MatrixXd m(rows, cols);
  for (int j = 0; j < cols; ++j) {
    for (int i = 0; i < rows; ++i) {
      m(i, j) = unit(*rng) < 0.01 ? std::numeric_limits<double>::infinity() : 0.1 * cell(*rng);
    }
  }
  return m;
}

class L1ColumnsIsa : public testing::TestWithParam<NearestIsa> {};

// Every build the processor runs (the others are skipped).
TEST_P(L1ColumnsIsa, FindsThePlainLoopsColumnAndSumBitForBit) {
  if (!NearestKernelSupports(GetParam())) GTEST_SKIP() << "this processor lacks that build";
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 0.7);
  for (int rows : {1, 3, 5, 40}) {
    for (int cols : {1, 7, 8, 9, 301}) {
      const Eigen::MatrixXd m = GridMatrix(rows, cols, &rng);
      const L1Columns packed(m, GetParam());
      std::vector<int> all(rows);
      for (int i = 0; i < rows; ++i) all[i] = i;
      for (int q = 0; q < 50; ++q) {
        std::vector<double> x(rows);
        // Half the queries are columns themselves (exact ties at 0), half anywhere.
        for (int i = 0; i < rows; ++i) x[i] = q % 2 ? m(i, q % cols) : unit(rng);
        const auto [j, cost] = packed.Nearest(x.data());
        const auto [pj, pcost] = PlainNearest(m, x, all);
        ASSERT_EQ(j, pj) << rows << " x " << cols << ", query " << q;
        ASSERT_EQ(std::memcmp(&cost, &pcost, sizeof(double)), 0) << cost << " vs " << pcost;
      }
    }
  }
}

TEST_P(L1ColumnsIsa, OverChosenRowsInTheirOrder) {
  if (!NearestKernelSupports(GetParam())) GTEST_SKIP() << "this processor lacks that build";
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 0.7);
  const Eigen::MatrixXd m = GridMatrix(30, 300, &rng);
  const L1Columns packed(m, GetParam());
  std::uniform_int_distribution<int> row(0, 29);
  for (int q = 0; q < 200; ++q) {
    const std::vector<int> rows = {row(rng), row(rng), row(rng)};
    const std::vector<double> x = {unit(rng), unit(rng), unit(rng)};
    const auto [j, cost] = packed.Nearest(x.data(), rows.data(), 3);
    const auto [pj, pcost] = PlainNearest(m, x, rows);
    ASSERT_EQ(j, pj);
    ASSERT_EQ(std::memcmp(&cost, &pcost, sizeof(double)), 0);
  }
}

INSTANTIATE_TEST_SUITE_P(Builds, L1ColumnsIsa,
                         testing::Values(NearestIsa::kAuto, NearestIsa::kAvx512, NearestIsa::kAvx2,
                                         NearestIsa::kBaseline));

TEST(L1Columns, EveryColumnInfiniteGivesTheFirst) {
  Eigen::MatrixXd m = Eigen::MatrixXd::Constant(2, 10, std::numeric_limits<double>::infinity());
  const double x[2] = {0.0, 0.0};
  const auto [j, cost] = L1Columns(m).Nearest(x);
  EXPECT_EQ(j, 0);
  EXPECT_TRUE(std::isinf(cost));
}

TEST(L1Columns, NoColumnsIsAnError) {
  EXPECT_THROW(L1Columns(Eigen::MatrixXd(3, 0)), InvalidInputError);
}

}  // namespace
}  // namespace symembed

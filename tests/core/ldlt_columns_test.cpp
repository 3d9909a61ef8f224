#include "core/ldlt_columns.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/errors.h"

namespace symembed {
namespace {

// A sparse symmetric positive definite matrix on a random graph of n nodes (a Laplacian plus a
// diagonal), its off-diagonal values scaled by `scale` and its diagonal shifted by `shift`, so
// that matrices of one pattern get different values.
Eigen::SparseMatrix<double> RandomSpd(int n, int edges, double scale, double shift,
                                      std::mt19937* rng) {
  std::uniform_int_distribution<int> node(0, n - 1);
  std::uniform_real_distribution<double> weight(0.1, 2.0);
  std::vector<Eigen::Triplet<double>> t;
  std::mt19937 pattern(7);  // the same pattern for every call
  for (int e = 0; e < edges; ++e) {
    const int i = node(pattern), j = node(pattern);
    if (i == j) continue;
    const double w = scale * weight(*rng);
    t.emplace_back(i, i, w);
    t.emplace_back(j, j, w);
    t.emplace_back(i, j, -w);
    t.emplace_back(j, i, -w);
  }
  for (int i = 0; i < n; ++i) t.emplace_back(i, i, shift + 0.01 * weight(*rng));
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

bool SameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

TEST(LdltColumns, EigensSolveBitForBitForOneToThreeColumns) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int n : {1, 2, 17, 300}) {
    SparseLdlt f[3];
    for (int c = 0; c < 3; ++c) {
      f[c].compute(RandomSpd(n, 4 * n, 1.0 + c, 0.5 * c + 1e-3, &rng));
      ASSERT_EQ(f[c].info(), Eigen::Success);
    }
    ASSERT_TRUE(SameLdltStructure(f[0], f[2]));
    Eigen::MatrixXd B(n, 3);
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) B(i, c) = normal(rng);
    }
    // Exact zeros, whose columns the lower solve skips, and a signed zero.
    B(0, 1) = 0.0;
    if (n > 1) B(n - 1, 2) = -0.0;
    for (int k = 1; k <= 3; ++k) {
      std::vector<const SparseLdlt*> factors;
      Eigen::MatrixXd expected(n, k);
      for (int c = 0; c < k; ++c) {
        factors.push_back(&f[(c + 1) % 3]);
        expected.col(c) = f[(c + 1) % 3].solve(B.col(c));
      }
      Eigen::MatrixXd X(n, k);
      LdltColumns(factors).Solve(B.leftCols(k), X);
      EXPECT_TRUE(SameBits(X, expected)) << "n " << n << " k " << k;
    }
    // One factor for two columns, as Eigen solves a block of two.
    const Eigen::MatrixXd expected = f[1].solve(B.rightCols<2>());
    Eigen::MatrixXd X(n, 2);
    LdltColumns({&f[1], &f[1]}).Solve(B.rightCols<2>(), X);
    EXPECT_TRUE(SameBits(X, expected)) << "n " << n;
  }
}

TEST(LdltColumns, RefusesFactorsOfAnotherStructureOrSize) {
  std::mt19937 rng(5);
  SparseLdlt a, b;
  a.compute(RandomSpd(20, 60, 1.0, 1.0, &rng));
  Eigen::SparseMatrix<double> other(20, 20);
  other.setIdentity();
  b.compute(other);
  EXPECT_FALSE(SameLdltStructure(a, b));
  Eigen::MatrixXd B = Eigen::MatrixXd::Ones(20, 2), X(20, 2);
  EXPECT_THROW(LdltColumns({&a, &b}), InvalidInputError);
  Eigen::MatrixXd wrong(19, 1), Y(19, 1);
  EXPECT_THROW(LdltColumns({&a}).Solve(wrong, Y), InvalidInputError);
  EXPECT_THROW(LdltColumns({}), InvalidInputError);
}

}  // namespace
}  // namespace symembed

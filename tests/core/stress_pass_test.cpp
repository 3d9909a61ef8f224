#include "core/mds/stress_pass.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/errors.h"

namespace symembed {
namespace {

// A symmetric dissimilarity matrix with zero diagonal, a configuration whose rows `dup` and
// `dup + 1` coincide (a pair at distance 0), and weights d^-2 (0 where d = 0).
struct Problem {
  Eigen::MatrixXd D, W, X;
};

Problem MakeProblem(int n, int dims, std::mt19937* rng) {
  std::uniform_real_distribution<double> uniform(0.1, 2.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  Problem p;
  p.D.setZero(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) p.D(i, j) = p.D(j, i) = uniform(*rng);
  }
  p.W = (p.D.array() > 0.0).select(p.D.array().pow(-2.0), 0.0).matrix();
  p.X.resize(n, dims);
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < dims; ++c) p.X(i, c) = normal(*rng);
  }
  if (n >= 3) p.X.row(n / 2 + 1) = p.X.row(n / 2);
  return p;
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

bool SameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

TEST(StressPass, EveryBuildGivesTheBaselineBits) {
  if (!NearestKernelSupports(NearestIsa::kAvx2)) GTEST_SKIP() << "no AVX2 on this processor";
  std::mt19937 rng(11);
  // Every row length modulo 4 and below 4 (n up to 40), longer rows, 1 to 5 dimensions (5 takes
  // the baseline in every build).
  for (int n = 1; n <= 40; ++n) {
    for (const int dims : {1, 2, 3, 4, 5}) {
      for (const int size : {n, n + 217}) {
        const Problem p = MakeProblem(size, dims, &rng);
        for (const bool weighted : {false, true}) {
          const Eigen::MatrixXd* W = weighted ? &p.W : nullptr;
          Eigen::MatrixXd bx_base, bx_avx2;
          const double base = StressPass(p.D, W, p.X, &bx_base, 2, NearestIsa::kBaseline);
          const double avx2 = StressPass(p.D, W, p.X, &bx_avx2, 2, NearestIsa::kAvx2);
          const double stress_only = StressPass(p.D, W, p.X, nullptr, 1, NearestIsa::kAvx2);
          SCOPED_TRACE(::testing::Message()
                       << "n " << size << ", dims " << dims << (weighted ? ", weighted" : ""));
          EXPECT_TRUE(SameBits(base, avx2)) << base << " vs " << avx2;
          EXPECT_TRUE(SameBits(base, stress_only)) << base << " vs " << stress_only;
          EXPECT_TRUE(SameBits(bx_base, bx_avx2));
        }
      }
    }
  }
}

TEST(StressPass, ComputesTheStressAndTheGuttmanProduct) {
  std::mt19937 rng(3);
  const Problem p = MakeProblem(23, 3, &rng);
  double stress = 0.0;
  Eigen::MatrixXd expected = Eigen::MatrixXd::Zero(23, 3);
  for (int i = 0; i < 23; ++i) {
    for (int j = 0; j < 23; ++j) {
      const double dist = (p.X.row(i) - p.X.row(j)).norm();
      if (j > i) stress += p.W(i, j) * std::pow(p.D(i, j) - dist, 2);
      if (dist > 0.0) expected.row(i) += p.W(i, j) * p.D(i, j) / dist * (p.X.row(i) - p.X.row(j));
    }
  }
  for (const NearestIsa isa : {NearestIsa::kAuto, NearestIsa::kBaseline}) {
    Eigen::MatrixXd bx;
    EXPECT_NEAR(StressPass(p.D, &p.W, p.X, &bx, 0, isa), stress, 1e-12 * stress);
    EXPECT_LT((bx - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
  }
}

TEST(StressPass, RefusesABuildTheProcessorLacks) {
  std::mt19937 rng(1);
  const Problem p = MakeProblem(5, 3, &rng);
  int refused = 0;
  for (const NearestIsa isa : {NearestIsa::kAvx2, NearestIsa::kAvx512}) {
    if (NearestKernelSupports(isa)) continue;
    EXPECT_THROW(StressPass(p.D, nullptr, p.X, nullptr, 1, isa), InternalError);
    ++refused;
  }
  if (refused == 0) GTEST_SKIP() << "this processor runs every build";
}

}  // namespace
}  // namespace symembed

#include "core/procrustes.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "core/errors.h"

namespace symembed {
namespace {

Eigen::MatrixXd RandomPoints(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd P(n, 3);
  for (int i = 0; i < n; ++i) P.row(i) << 2.0 * u(rng), 1.0 * u(rng), 0.5 * u(rng);
  return P;
}

Eigen::Matrix3d SomeRotation() {
  return (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
          Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

TEST(Procrustes, RecoversRigidMotionAndScale) {
  const Eigen::MatrixXd X = RandomPoints(50, 1);
  const Eigen::Matrix3d R = SomeRotation();
  const Eigen::RowVector3d t(0.3, -2.0, 5.0);
  const Eigen::MatrixXd Y = ((2.5 * X * R).rowwise() + t).eval();
  ProcrustesOptions options;
  options.allow_scale = true;
  const ProcrustesFit fit = FitProcrustes(X, Y, options);
  // Exact data: only rounding error remains.
  EXPECT_LT((fit.R - Eigen::MatrixXd(R)).norm(), 1e-12);
  EXPECT_NEAR(fit.scale, 2.5, 1e-12);
  EXPECT_LT(fit.rms_residual, 1e-12);
  EXPECT_EQ(fit.det_sign, 1);
  EXPECT_LT((ApplyProcrustes(fit, X) - Y).norm(), 1e-10);
}

TEST(Procrustes, DetectsReflection) {
  const Eigen::MatrixXd X = RandomPoints(50, 2);
  Eigen::MatrixXd Y = X * SomeRotation();
  Y.col(1) *= -1.0;
  EXPECT_EQ(ProcrustesReflection(X, Y), -1);
  EXPECT_EQ(ProcrustesReflection(X, X * SomeRotation()), 1);
  const ProcrustesFit orthogonal = FitProcrustes(X, Y);
  EXPECT_LT(orthogonal.rms_residual, 1e-12);  // exact with a reflection allowed
  ProcrustesOptions proper;
  proper.allow_reflection = false;
  const ProcrustesFit rotation = FitProcrustes(X, Y, proper);
  EXPECT_EQ(rotation.det_sign, 1);
  EXPECT_NEAR(rotation.R.determinant(), 1.0, 1e-12);
  // A proper rotation cannot fit a mirror image of a non-planar set: residual of the order of
  // the smallest extent (0.5 / sqrt(3) per coordinate for uniform points).
  EXPECT_GT(rotation.rms_residual, 0.1);
}

TEST(Procrustes, ConditioningFlagsPlanarSets) {
  Eigen::MatrixXd X = RandomPoints(30, 3);
  EXPECT_GT(FitProcrustes(X, X).conditioning, 0.01);
  X.col(2).setZero();
  EXPECT_LT(FitProcrustes(X, X).conditioning, 1e-12);
}

TEST(Procrustes, RejectsMismatchedShapes) {
  EXPECT_THROW(FitProcrustes(Eigen::MatrixXd::Zero(4, 3), Eigen::MatrixXd::Zero(5, 3)),
               InvalidInputError);
  EXPECT_THROW(FitProcrustes(Eigen::MatrixXd::Zero(4, 3), Eigen::MatrixXd::Zero(4, 2)),
               InvalidInputError);
}

// Swapping two points of a square moves each by the side; the measure does not change with the
// point set's scale, and is -1 for an image outside the set or a set without extent.
TEST(SelfMapDisplacement, MeanMoveOverTheRmsRadiusScaleFree) {
  Eigen::MatrixXd P(4, 2);
  P << 0, 0, 1, 0, 1, 1, 0, 1;
  const std::vector<int> swap = {1, 0, 2, 3};
  const double expected = (1.0 + 1.0) / 4 / RmsRadius(P);
  EXPECT_NEAR(SelfMapDisplacement(P, swap), expected, 1e-12);
  EXPECT_NEAR(SelfMapDisplacement(Eigen::MatrixXd(3.0 * P), swap), expected, 1e-12);
  EXPECT_EQ(SelfMapDisplacement(P, {0, 1, 2, 3}), 0.0);
  EXPECT_EQ(SelfMapDisplacement(P, {1, 0, 2, 4}), -1.0);
  EXPECT_EQ(SelfMapDisplacement(P, {1, 0}), -1.0);
  EXPECT_EQ(SelfMapDisplacement(Eigen::MatrixXd::Ones(4, 2), swap), -1.0);
}

}  // namespace
}  // namespace symembed

#include "core/canonical_frame.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "tests/test_util.h"

namespace symembed {
namespace {

// Rotations about x keep the symmetry plane x = 0.
Eigen::Matrix3d RotX(double a) { return Eigen::AngleAxisd(a, Eigen::Vector3d::UnitX()).toRotationMatrix(); }

TEST(CanonicalFrame, ProperRotationCentredPrincipalAxes) {
  const Surface figure = testing::SymmetricFigure();
  const Eigen::MatrixX3d Y = (figure.V * RotX(0.7).transpose()).rowwise() +
                             Eigen::RowVector3d(0.0, 3.0, -2.0);
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  const Eigen::MatrixX3d C = CanonicalFrame(Y, &R, &t);
  // Tolerances: rounding of sums over ~600 points of size ~1.
  EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
  EXPECT_NEAR((R * R.transpose() - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(R(0, 0)), 1.0, 1e-12);  // the plane normal stays on x
  EXPECT_NEAR(C.col(1).mean(), 0.0, 1e-12);
  EXPECT_NEAR(C.col(2).mean(), 0.0, 1e-12);
  EXPECT_NEAR((C - ((Y * R.transpose()).rowwise() + t.transpose())).norm(), 0.0, 1e-12);
  // Principal axes: y carries the largest in-plane variance, y and z are uncorrelated.
  EXPECT_GT(C.col(1).squaredNorm(), C.col(2).squaredNorm());
  EXPECT_NEAR(C.col(1).dot(C.col(2)) / C.rows(), 0.0, 1e-12);
  EXPECT_GT(C.col(1).array().cube().sum(), 0.0);
  EXPECT_GT(C.col(2).array().cube().sum(), 0.0);
}

TEST(CanonicalFrame, AxisRatioIsTheRatioOfTheInPlaneDeviations) {
  // Four points in the plane x = 0: deviations 2 along one in-plane axis, 1 along the other,
  // turned about x so the axes are not the coordinate axes.
  Eigen::MatrixX3d Y(4, 3);
  Y << 0, 2, 0, 0, -2, 0, 0, 0, 1, 0, 0, -1;
  double ratio = 0.0;
  CanonicalFrame(Y * RotX(0.3).transpose(), nullptr, nullptr, &ratio);
  EXPECT_NEAR(ratio, 0.5, 1e-12);
}

TEST(CanonicalFrame, SameFrameWhateverTheRotationAboutTheNormal) {
  const Surface figure = testing::SymmetricFigure();
  const Eigen::MatrixX3d reference = CanonicalFrame(figure.V);
  for (double angle : {0.3, 1.9, M_PI, 4.4}) {
    const Eigen::MatrixX3d C = CanonicalFrame(figure.V * RotX(angle).transpose());
    // Tolerance: rounding only; the third-moment signs are far from zero for this figure.
    EXPECT_NEAR((C - reference).cwiseAbs().maxCoeff(), 0.0, 1e-9) << "angle " << angle;
  }
  // The figure is nearly axis-aligned (its parts are; their y-z covariance is small): R nearly
  // only changes signs.
  Eigen::Matrix3d R;
  CanonicalFrame(figure.V, &R);
  EXPECT_NEAR((R.cwiseAbs() - Eigen::Matrix3d::Identity()).norm(), 0.0, 0.05);
}

}  // namespace
}  // namespace symembed

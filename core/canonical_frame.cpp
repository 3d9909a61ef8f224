#include "core/canonical_frame.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace symembed {

Eigen::MatrixX3d CanonicalFrame(const Eigen::MatrixX3d& Y, Eigen::Matrix3d* R_out,
                                Eigen::Vector3d* t_out, double* axis_ratio) {
  if (Y.rows() < 3) throw InvalidInputError("CanonicalFrame: fewer than 3 points");
  if (!Y.allFinite()) throw InvalidInputError("CanonicalFrame: non-finite coordinates");
  Eigen::Vector3d centroid = Y.colwise().mean().transpose();
  centroid.x() = 0.0;
  const Eigen::MatrixX3d C = Y.rowwise() - centroid.transpose();

  // Principal axes of the in-plane (y, z) coordinates.
  const Eigen::MatrixX2d P = C.rightCols<2>();
  const Eigen::Matrix2d cov = P.transpose() * P / static_cast<double>(P.rows());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
  // Eigenvalues ascending: column 1 is the largest-variance direction.
  Eigen::Vector3d axis_y(0.0, eig.eigenvectors()(0, 1), eig.eigenvectors()(1, 1));
  Eigen::Vector3d axis_z(0.0, eig.eigenvectors()(0, 0), eig.eigenvectors()(1, 0));
  auto third_moment = [&](const Eigen::Vector3d& axis) {
    return (C * axis).array().cube().sum();
  };
  if (third_moment(axis_y) < 0.0) axis_y = -axis_y;
  if (third_moment(axis_z) < 0.0) axis_z = -axis_z;
  const Eigen::Vector3d axis_x = axis_y.cross(axis_z);

  Eigen::Matrix3d R;
  R.row(0) = axis_x.transpose();
  R.row(1) = axis_y.transpose();
  R.row(2) = axis_z.transpose();
  const Eigen::Vector3d t = -R * centroid;
  if (axis_ratio) {
    const double large = std::max(eig.eigenvalues()(1), 0.0);
    *axis_ratio = large > 0.0 ? std::sqrt(std::max(eig.eigenvalues()(0), 0.0) / large) : 1.0;
  }
  if (R_out) *R_out = R;
  if (t_out) *t_out = t;
  return (Y * R.transpose()).rowwise() + t.transpose();
}

}  // namespace symembed

#include "stages/symmetrize/symmetrize_costs.h"

#include <cmath>
#include <utility>

namespace symembed {

bool EdgeStressCost::Evaluate(double const* const* parameters, double* residuals,
                              double** jacobians) const {
  const double* a = parameters[0];
  const double* b = parameters[1];
  const double d[3] = {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  residuals[0] = (length - d0_) * inv_scale_;
  if (jacobians) {
    // The gradient of ||a - b|| is undefined at a = b; zero there (a subgradient).
    const double g = length > 0.0 ? inv_scale_ / length : 0.0;
    for (int c = 0; c < 3; ++c) {
      if (jacobians[0]) jacobians[0][c] = g * d[c];
      if (jacobians[1]) jacobians[1][c] = -g * d[c];
    }
  }
  return true;
}

LinearResidualCost::LinearResidualCost(std::vector<Eigen::Matrix3d> A, double weight)
    : A_(std::move(A)), weight_(weight) {
  set_num_residuals(3);
  for (size_t b = 0; b < A_.size(); ++b) mutable_parameter_block_sizes()->push_back(3);
}

bool LinearResidualCost::Evaluate(double const* const* parameters, double* residuals,
                                  double** jacobians) const {
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r.setZero();
  for (size_t b = 0; b < A_.size(); ++b) {
    r += A_[b] * Eigen::Map<const Eigen::Vector3d>(parameters[b]);
  }
  r *= weight_;
  if (jacobians) {
    for (size_t b = 0; b < A_.size(); ++b) {
      if (!jacobians[b]) continue;
      // Ceres Jacobian blocks are row-major (residual x parameter).
      Eigen::Map<Eigen::Matrix<double, 3, 3, Eigen::RowMajor>> J(jacobians[b]);
      J = weight_ * A_[b];
    }
  }
  return true;
}

bool OnPlaneCost::Evaluate(double const* const* parameters, double* residuals,
                           double** jacobians) const {
  residuals[0] = weight_ * parameters[0][0];
  if (jacobians && jacobians[0]) {
    jacobians[0][0] = weight_;
    jacobians[0][1] = 0.0;
    jacobians[0][2] = 0.0;
  }
  return true;
}

bool AnchorCost::Evaluate(double const* const* parameters, double* residuals,
                          double** jacobians) const {
  for (int c = 0; c < 3; ++c) residuals[c] = weight_ * (parameters[0][c] - a0_[c]);
  if (jacobians && jacobians[0]) {
    for (int k = 0; k < 9; ++k) jacobians[0][k] = (k % 4 == 0) ? weight_ : 0.0;
  }
  return true;
}

}  // namespace symembed

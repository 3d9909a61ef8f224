// Ceres residuals of the `ceres` symmetrize stage, with analytic Jacobians (checked against
// numeric differentiation in tests/stages/symmetrize_test.cpp). Positions are 3-vectors.
#pragma once

#include <ceres/ceres.h>

#include <Eigen/Core>
#include <vector>

namespace symembed {

// r = (||a - b|| - d0) * inv_scale: keeps the length of a sample-graph edge (stress term).
class EdgeStressCost : public ceres::SizedCostFunction<1, 3, 3> {
 public:
  EdgeStressCost(double d0, double inv_scale) : d0_(d0), inv_scale_(inv_scale) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  double d0_;
  double inv_scale_;
};

// r = weight * sum_b A_b x_b over any number of distinct 3-vector blocks x_b (3 residuals).
// The symmetry term M x_i - sum_j c_ij x_j is A = {M - c_ii I, -c_ij I, ...}; with one mirror
// sample, {M, -I}.
class LinearResidualCost : public ceres::CostFunction {
 public:
  LinearResidualCost(std::vector<Eigen::Matrix3d> A, double weight);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  std::vector<Eigen::Matrix3d> A_;
  double weight_;
};

// r = weight * a_x: a self-symmetric sample stays on the plane x = 0.
class OnPlaneCost : public ceres::SizedCostFunction<1, 3> {
 public:
  explicit OnPlaneCost(double weight) : weight_(weight) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  double weight_;
};

// r = weight * (a - a0): optional pull towards the unsymmetrized position.
class AnchorCost : public ceres::SizedCostFunction<3, 3> {
 public:
  AnchorCost(const double* a0, double weight) : a0_{a0[0], a0[1], a0[2]}, weight_(weight) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  double a0_[3];
  double weight_;
};

}  // namespace symembed

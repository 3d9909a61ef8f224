// Ceres residuals of the `ceres` symmetrize stage, with analytic Jacobians (checked against
// numeric differentiation in tests/stages/symmetrize_test.cpp). Positions are 3-vectors.
#pragma once

#include <ceres/ceres.h>

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

// r = weight * (M a - b), M = diag(-1, 1, 1): a's mirror image should be its mirror sample b.
class MirrorPairCost : public ceres::SizedCostFunction<3, 3, 3> {
 public:
  explicit MirrorPairCost(double weight) : weight_(weight) {}
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
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

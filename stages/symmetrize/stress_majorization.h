// Stress majorization of the `ceres` symmetrize stage's energy, used as its warm start.
//
// The energy (ceres_symmetrize.h, before the common 1 / size^2 factor)
//   E(X) = sum_{(i,j)} (||x_i - x_j|| - d_ij)^2 + sum_i s_i ||M x_i - sum_j w_ij x_j||^2
//        + p sum_{i in plane} x_{i,x}^2 + a sum_i ||x_i - y_i||^2
// is bounded above at the current positions Z by the quadratic obtained from
// ||x_i - x_j|| >= (x_i - x_j) . u_ij, u_ij = (z_i - z_j) / ||z_i - z_j||, which touches E at Z.
// Minimising the bound is one sparse linear solve per coordinate with a matrix that does not
// depend on Z (M is diagonal, so the coordinates decouple): factor once, then every iteration
// is a right-hand side and three back-substitutions, and E never increases [Gansner, Koren &
// North 2004, Graph drawing by stress majorization; de Leeuw 1977, SMACOF]. Each iteration is
// orders of magnitude cheaper than a Levenberg-Marquardt step with a fresh factorisation, so a
// few hundred of them bring the start of the Ceres solve close to its minimum.
#pragma once

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace symembed {

struct SymmetrizeEnergy {
  std::vector<std::pair<int, int>> edges;               // stress graph, i < j
  std::vector<double> lengths;                          // d_ij per edge
  std::vector<std::vector<std::pair<int, double>>> mirror;  // per sample: (j, w_ij)
  Eigen::VectorXd symmetry_weight;                      // s_i per sample (>= 0)
  std::vector<int> on_plane;                            // samples held on x = 0
  double plane_weight = 0.0;                            // p
  double anchor_weight = 0.0;                           // a
  Eigen::MatrixX3d anchor;                              // y_i (#S x 3), used when a > 0

  // E(X) as above. X: #S x 3.
  double Evaluate(const Eigen::MatrixX3d& X) const;
};

struct MajorizationResult {
  Eigen::MatrixX3d X;
  int iterations = 0;
  double energy_before = 0.0, energy_after = 0.0;
};

// Up to max_iterations majorization steps from X0, stopping once an iteration lowers E by less
// than relative_tolerance * E. Throws InvalidInputError when the systems cannot be factored.
MajorizationResult MajorizeSymmetrizeEnergy(const SymmetrizeEnergy& energy,
                                            const Eigen::MatrixX3d& X0, int max_iterations,
                                            double relative_tolerance);

}  // namespace symembed

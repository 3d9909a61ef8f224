// Symmetrize stage `ceres`: deform the 3D embedding so that it becomes symmetric about its
// symmetry plane while keeping its shape.
//
// With the plane moved to x = 0 (MovePlaneToX0) and sample positions x_i (#S x 3) as unknowns,
// Ceres minimises (all residuals divided by the size s of the sample set, so weights are
// scale-free)
//   sum_{(i,j) in kNN graph} (||x_i - x_j|| - d0_ij)^2                     shape (stress)
// + symmetry_weight * sum_i c_i ||M x_i - x_sigma(i)||^2, M = diag(-1,1,1)   symmetry
// + plane_weight * sum_{i: sigma(i) = i} x_i,x^2                          self-symmetric samples
// + anchor_weight * sum_i ||x_i - y_i||^2                                 (optional, off)
// where d0_ij = ||y_i - y_j|| in the unsymmetrized embedding, the graph is the symmetric k-NN
// graph of the samples there, and c_i the symmetry confidence. Started from y. Dense vertices
// follow the samples (FollowSamples). Asymmetry is reported before and after.
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence;
// [Agarwal et al.] Ceres Solver.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "registry/types.h"

namespace symembed {

struct CeresSymmetrizeOptions {
  // Weight of the symmetry term relative to the stress term.
  double symmetry_weight = 10.0;
  // Weight keeping self-symmetric samples (sigma(i) = i) on the plane.
  double plane_weight = 10.0;
  // Weight pulling samples to their unsymmetrized positions (0: off).
  double anchor_weight = 0.0;
  // Neighbours per sample in the stress graph.
  int graph_neighbors = 10;
  // Nearest samples whose displacements a dense vertex follows.
  int follow_neighbors = 8;
  // Ceres limits.
  int max_iterations = 100;
  double function_tolerance = 1e-10;
  int threads = 1;

  bool IsValid(std::string* error) const;
};

// Y: #V x 3 embedding; samples: #S ids; symmetry: plane in Y's coordinates, sigma (#S),
// confidence (#S, or empty = all 1). Returns #V x 3 symmetric about x = 0. Throws
// InvalidInputError on inconsistent input, ConfigError on invalid options.
SymmetrizeResult SymmetrizeCeres(const Eigen::MatrixXd& Y, const std::vector<int>& samples,
                                 const SymmetryResult& symmetry,
                                 const CeresSymmetrizeOptions& options);

// Relative stress of sample positions X against the reference P on P's symmetric k-NN graph:
// sqrt(sum (||x_i - x_j|| - ||p_i - p_j||)^2 / sum ||p_i - p_j||^2). P, X: #S x 3.
double GraphStress(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& X, int k);

// The symmetric k-NN graph of P (#S x 3) as pairs i < j.
std::vector<std::pair<int, int>> KnnGraphEdges(const Eigen::MatrixX3d& P, int k);

}  // namespace symembed

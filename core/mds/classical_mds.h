// Classical (Torgerson) MDS and landmark MDS.
//
// Classical MDS: B = -1/2 J D^2 J (J = I - 11^T/n, D^2 squared distances elementwise); with the
// top `dims` eigenpairs (lambda_k, v_k) of B, x_i = (sqrt(lambda_k) v_k(i))_k. Negative
// eigenvalues (non-Euclidean D) contribute zero columns. Eigenvector signs are whatever the
// solver returns (deterministic, but arbitrary with respect to the input shape).
// Landmark MDS places any point a from its squared distances delta_a to the n landmarks:
// x_a = -1/2 L# (delta_a - delta_mu), L# rows v_k^T / sqrt(lambda_k), delta_mu the mean
// column of D^2; it reproduces the landmarks' own coordinates exactly.
//
// [Torgerson 1952] Multidimensional scaling: I. Theory and method.
// [Tenenbaum et al. 2000] A global geometric framework for nonlinear dimensionality reduction.
// [de Silva & Tenenbaum 2004] Sparse multidimensional scaling using landmark points.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace symembed {

struct ClassicalMdsOptions {
  int dims = 3;  // embedding dimension, >= 1 and < n
  // Above this n the top eigenpairs come from Spectra's Lanczos solver on the dense matrix;
  // at or below, from a full dense eigendecomposition.
  int dense_limit = 200;
  double eigen_tolerance = 1e-10;  // Spectra relative tolerance
  int eigen_max_iterations = 1000;

  bool IsValid(std::string* error) const;
};

struct ClassicalMdsResult {
  Eigen::MatrixXd X;             // n x dims, centred
  Eigen::VectorXd eigenvalues;   // dims, descending (may be <= 0 for non-Euclidean input)
  Eigen::MatrixXd eigenvectors;  // n x dims, unit columns
  Eigen::VectorXd mean_squared;  // n: delta_mu, the mean of each column of D^2
  int solver_iterations = 0;     // Lanczos restarts (0 for the dense path)
};

// D: n x n distances (symmetric part used), n >= dims + 1. Throws InvalidInputError on bad D,
// ConfigError on invalid options, SolverError when the eigensolver does not converge.
ClassicalMdsResult ClassicalMds(const Eigen::MatrixXd& D, const ClassicalMdsOptions& options = {});

// Landmark MDS for queries: Dq is n x m distances from each landmark to each query point (the
// columns `columns` of Dq, or all of them when empty). Returns (#columns or m) x dims.
// Eigenpairs with lambda <= 0 give zero coordinates.
Eigen::MatrixXd LandmarkMds(const ClassicalMdsResult& mds, const Eigen::MatrixXd& Dq,
                            const std::vector<int>& columns = {});

}  // namespace symembed

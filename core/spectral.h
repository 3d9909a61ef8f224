// Laplace-Beltrami eigenbasis of a triangle mesh.
//
// The smallest k eigenpairs of the generalised problem L phi = lambda M phi, with L the cotangent
// stiffness matrix and M the (lumped or consistent) mass matrix of core/laplacian.h, computed by
// shift-and-invert Lanczos (Spectra, B-inner product) on one sparse LDL^T factorisation of
// L - sigma M with a small negative shift sigma.
//
// [Levy 2006] Laplace-Beltrami eigenfunctions towards an algorithm that "understands" geometry;
// [Vallet & Levy 2008] Spectral geometry processing with manifold harmonics.
#pragma once

#include <Eigen/Core>
#include <map>
#include <string>

#include "core/laplacian.h"
#include "core/mesh.h"

namespace symembed {

struct LaplaceBasis {
  Eigen::VectorXd evals;  // k, ascending (first ~0 on each connected component), units 1/length^2
  Eigen::MatrixXd evecs;  // #V x k, M-orthonormal: evecs^T M evecs = I
  Eigen::VectorXd mass;   // #V lumped vertex areas (diagonal of M when lumped)

  int NumVertices() const { return static_cast<int>(evecs.rows()); }
  int NumEigenpairs() const { return static_cast<int>(evals.size()); }
};

struct LaplaceBasisOptions {
  // Number of eigenpairs; must be at least 1 and less than the number of vertices with mass.
  int k = 100;
  // Mass matrix of the generalised problem. `mass` in the result is always the lumped areas.
  MassType mass = MassType::kLumped;
  // Relative accuracy of the eigenvalues (Spectra's convergence tolerance).
  double tolerance = 1e-10;
  // Maximum number of restarts of the Lanczos iteration.
  int max_iterations = 1000;

  bool IsValid(std::string* error) const;
};

// Computes the smallest options.k eigenpairs of the Laplace-Beltrami operator of `surface`.
//
// Vertices with zero lumped area (unreferenced, or touching only degenerate faces) are left out
// of the problem; their rows of evecs are zero and their mass is zero. Open boundaries get the
// natural (Neumann) condition. Several connected components give several ~0 eigenvalues.
// A few more eigenpairs than k are computed and dropped, so that a repeated eigenvalue cut by k
// is returned with its full multiplicity. Signs of eigenvectors are fixed (largest-magnitude
// entry positive); eigenvectors of repeated eigenvalues are any M-orthonormal basis of their
// eigenspace.
//
// Throws ConfigError when the options are invalid, InvalidInputError when k is not less than the
// number of vertices with mass, SolverError when the factorisation or the iteration fails.
LaplaceBasis ComputeLaplaceBasis(const Surface& surface, const LaplaceBasisOptions& options);

// The spectrum's range for signatures built from eigenvalues: *lambda_max the largest eigenvalue
// and *lambda_1 the smallest above 1e-8 lambda_max (the ~0 eigenvalues of the constant
// eigenfunctions excluded). *lambda_1 is not positive when no eigenvalue is.
void PositiveEigenvalueRange(const Eigen::VectorXd& evals, double* lambda_1, double* lambda_max);

// The first k eigenpairs of basis (k = -1: all of them) into *out, reusing its storage when it
// already has the sizes: a per-pair stage that keeps one basis per thread copies it without
// allocating (fresh megabytes of eigenvectors cost more in page faults than in copying). Throws
// InvalidInputError when basis is inconsistent or holds fewer than k eigenpairs.
void LeadingEigenpairs(const LaplaceBasis& basis, int k, LaplaceBasis* out);
LaplaceBasis LeadingEigenpairs(const LaplaceBasis& basis, int k);

}  // namespace symembed

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

// Per-shape storage of a basis in ShapeData::aux (shared by the refine stages and the `hks` flip
// scorer, so that a shape's basis is computed once):
//   "lb_evals"  k x 1   eigenvalues, ascending
//   "lb_evecs"  #V x k  M-orthonormal eigenvectors
//   "lb_mass"   #V x 1  lumped vertex areas
inline constexpr const char* kLbEvalsKey = "lb_evals";
inline constexpr const char* kLbEvecsKey = "lb_evecs";
inline constexpr const char* kLbMassKey = "lb_mass";

using AuxMap = std::map<std::string, Eigen::MatrixXd>;

// Stores basis under the three keys (replacing what was there).
void PutLaplaceBasis(const LaplaceBasis& basis, AuxMap* aux);

// True when aux holds a consistent basis with at least k eigenpairs for a #V = num_vertices
// shape.
bool HasLaplaceBasis(const AuxMap& aux, int k, int num_vertices);

// The spectrum's range for signatures built from eigenvalues: *lambda_max the largest eigenvalue
// and *lambda_1 the smallest above 1e-8 lambda_max (the ~0 eigenvalues of the constant
// eigenfunctions excluded). *lambda_1 is not positive when no eigenvalue is.
void PositiveEigenvalueRange(const Eigen::VectorXd& evals, double* lambda_1, double* lambda_max);

// The first k eigenpairs stored in aux (k = -1: all of them). Throws InvalidInputError when the
// keys are missing, inconsistent, or hold fewer than k eigenpairs.
LaplaceBasis GetLaplaceBasis(const AuxMap& aux, int k = -1);

// The same into *basis, reusing its storage when it already has the sizes: a per-pair stage that
// keeps one basis per thread copies it without allocating (fresh megabytes of eigenvectors cost
// more in page faults than in copying).
void GetLaplaceBasis(const AuxMap& aux, int k, LaplaceBasis* basis);

// Computes the basis with options into aux unless aux already holds at least options.k
// eigenpairs for this surface. Returns true when it computed.
bool EnsureLaplaceBasis(const Surface& surface, const LaplaceBasisOptions& options, AuxMap* aux);

// Merges per-shape data that stages prepared separately: entries of `from` replace those of
// `into`, except the Laplace-Beltrami basis, of which the one with more eigenpairs is kept (its
// leading eigenpairs serve every stage that asked for fewer, so a stage preparing a small basis
// never takes away the larger one another stage needs).
void MergeAux(AuxMap from, AuxMap* into);

}  // namespace symembed

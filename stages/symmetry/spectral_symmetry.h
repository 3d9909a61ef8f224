// Intrinsic reflective symmetry seen through the low Laplace-Beltrami eigenfunctions.
//
// An intrinsic isometry T of a surface maps each eigenfunction of a simple eigenvalue to itself
// up to sign: phi_j o T = +-phi_j. A left-right symmetry is therefore a sign flip of some of the
// global point signature coordinates phi_j / sqrt(lambda_j), and its self map is the nearest
// neighbour in the flipped coordinates [Ovsjanikov et al. 2008] Global intrinsic symmetries of
// shapes. The eigenfunctions change smoothly with the metric, so a shape whose geodesic
// distances are not symmetric (one side of a bent body compressed) keeps nearly symmetric or
// antisymmetric low eigenfunctions, where a reflection of its distance embedding no longer exists.
//
// An eigenvalue of multiplicity m (or m eigenvalues too close for the discretisation to tell
// apart, as the limbs of a human give) has an m-dimensional eigenspace, and an isometry maps
// each eigenfunction into that space rather than onto +-itself: the check measures how much of
// phi_j o sigma stays in the span of the eigenfunctions whose eigenvalues lie within a relative
// tolerance of lambda_j.
//
// Used by the `plane2d` symmetry stage, both to propose self maps (one per sign pattern) and to
// check every candidate self map.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/range.h"

namespace symembed {

struct SpectralSymmetryOptions {
  // Eigenfunctions used, after the constant one (0: the spectral check and candidates are off).
  int num_eigenfunctions = 8;
  static constexpr Range kNumEigenfunctions = Range::Closed(0, 12);
  // Sign patterns kept as candidates, those of lowest SignFlipCandidate::score.
  int num_candidates = 4;
  static constexpr Range kNumCandidates = Range::AtLeast(0);
  // The candidates chosen by distances alone stand when their self map's SpectralConsistency is
  // at least this; below it the sign-flip candidates join and the criterion adds the weighted
  // inconsistency. 1: always (a consistency of exactly 1 is a symmetry of the eigenfunctions).
  double min_consistency = 1.0;
  static constexpr Range kMinConsistency = Range::Closed(0.0, 1.0);
  // Weight of the spectral inconsistency (1 - SpectralConsistency) in the choice of candidate.
  double weight = 0.25;
  static constexpr Range kWeight = Range::AtLeast(0.0);
  // Eigenvalues within this relative distance of lambda_j count as one eigenspace with it in
  // SpectralConsistency (0: every eigenfunction on its own).
  double eigenvalue_tolerance = 0.05;
  static constexpr Range kEigenvalueTolerance = Range::Closed(0.0, 1.0);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("spectral_eigenfunctions", self.num_eigenfunctions, kNumEigenfunctions);
    visit("spectral_candidates", self.num_candidates, kNumCandidates);
    visit("spectral_min_consistency", self.min_consistency, kMinConsistency);
    visit("spectral_weight", self.weight, kWeight);
    visit("spectral_eigenvalue_tolerance", self.eigenvalue_tolerance, kEigenvalueTolerance);
  }
  bool IsValid(std::string* error) const { return NoViolation(FieldViolation(*this), error); }
};

// Global point signature of the samples: #S x K, column j = phi_(j+1) / sqrt(lambda_(j+1)) at the
// samples, for the K = num_eigenfunctions lowest non-constant eigenpairs (the ~0 eigenvalue of
// every connected component is skipped). Throws InvalidInputError when the surface has too few
// vertices, SolverError when the eigensolver fails. evals, when given, receives the K eigenvalues.
Eigen::MatrixXd SampleSpectralCoordinates(const Surface& surface, const std::vector<int>& samples,
                                          int num_eigenfunctions, Eigen::VectorXd* evals = nullptr);

struct SignFlipCandidate {
  unsigned pattern = 0;      // bit j set: coordinate j flipped
  std::vector<int> sigma;    // #S: sample -> nearest sample to its flipped coordinates
  Eigen::VectorXd residual;  // #S: distance to that nearest sample
  double score = 0.0;        // TruncatedScore of the residuals (reflection_search.h)
  double fixed_fraction = 0.0;  // FixedFraction of sigma
};

// The num_candidates sign patterns (out of the 2^K - 1 that flip at least one coordinate) whose
// self maps have the lowest score, best first; size is the RMS radius of G. K <= 12. The nearest
// neighbours are searched on `threads` threads (0: all cores); the result does not depend on them.
std::vector<SignFlipCandidate> SignFlipCandidates(const Eigen::MatrixXd& G, int num_candidates,
                                                  double outlier_distance, int threads = 1);

// How well sigma (#S) commutes with the eigenfunctions: mean over the columns g_j of G of the
// norm of the projection of (g_j o sigma) / |g_j o sigma| onto the span of the columns g_k with
// |lambda_k - lambda_j| <= tolerance * lambda_j (evals: the K eigenvalues; empty or tolerance
// 0: g_j alone, and the term is |<g_j, g_j o sigma>| / (|g_j| |g_j o sigma|)). 1 when sigma maps
// every such span onto itself; small for a self map that is not an intrinsic symmetry. Throws
// InvalidInputError when evals is neither empty nor of size K.
double SpectralConsistency(const Eigen::MatrixXd& G, const std::vector<int>& sigma,
                           const Eigen::VectorXd& evals = Eigen::VectorXd(),
                           double tolerance = 0.0);

}  // namespace symembed

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
// Used by the `plane2d` symmetry stage, both to propose self maps (one per sign pattern) and to
// check every candidate self map (how far phi_j o sigma is from +-phi_j).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/mesh.h"

namespace symembed {

struct SpectralSymmetryOptions {
  // Eigenfunctions used, after the constant one (0: the spectral check and candidates are off).
  int num_eigenfunctions = 8;
  // Sign patterns kept as candidates, those of lowest SignFlipCandidate::score.
  int num_candidates = 4;
  // The candidates chosen by distances alone stand when their self map's SpectralConsistency is
  // at least this; below it the sign-flip candidates join and the criterion adds the weighted
  // inconsistency (1: always).
  double min_consistency = 0.4;
  // Weight of the spectral inconsistency (1 - SpectralConsistency) in the choice of candidate.
  double weight = 1.0;

  bool IsValid(std::string* error) const;
};

// Global point signature of the samples: #S x K, column j = phi_(j+1) / sqrt(lambda_(j+1)) at the
// samples, for the K = num_eigenfunctions lowest non-constant eigenpairs (the ~0 eigenvalue of
// every connected component is skipped). Throws InvalidInputError when the surface has too few
// vertices, SolverError when the eigensolver fails.
Eigen::MatrixXd SampleSpectralCoordinates(const Surface& surface, const std::vector<int>& samples,
                                          int num_eigenfunctions);

struct SignFlipCandidate {
  unsigned pattern = 0;      // bit j set: coordinate j flipped
  std::vector<int> sigma;    // #S: sample -> nearest sample to its flipped coordinates
  Eigen::VectorXd residual;  // #S: distance to that nearest sample
  double score = 0.0;        // TruncatedScore of the residuals (reflection_search.h)
  double fixed_fraction = 0.0;  // FixedFraction of sigma
};

// The num_candidates sign patterns (out of the 2^K - 1 that flip at least one coordinate) whose
// self maps have the lowest score, best first; size is the RMS radius of G. K <= 12.
std::vector<SignFlipCandidate> SignFlipCandidates(const Eigen::MatrixXd& G, int num_candidates,
                                                  double outlier_distance);

// How well sigma (#S) commutes with the eigenfunctions: mean over the columns g of G of
// |<g, g o sigma>| / (|g| |g o sigma|). 1 when every column is symmetric or antisymmetric under
// sigma; small for a self map that is not an intrinsic symmetry.
double SpectralConsistency(const Eigen::MatrixXd& G, const std::vector<int>& sigma);

}  // namespace symembed

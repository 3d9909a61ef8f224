// Refined term of the flip scorers: how well each of the best candidates' maps agrees with the
// surfaces once ZoomOut has made it accurate.
//
// On a human, the candidate maps of the right rotation and of the rotation by pi about the
// vertical axis differ by a front-back reflection composed with the left-right one. The
// canonical embedding is thin front to back, so the nearest-neighbour maps carry almost no
// front-back information, and the short ZoomOut of the orientation term (orientation.h), which
// starts at a few eigenfunctions where a human's front and back look alike, can settle either
// candidate on a front-back reflection. This term refines the best `candidates` candidates (by
// the other terms) with ZoomOut [Melzi et al. 2019] on the source samples, from a basis size at
// which the two are still apart (k_start 20), and measures the refined map of the samples twice:
//   disagreement d_k = FeatureDisagreement of the shape index and curvedness over the samples
//                      (extrinsic.h), which the right map preserves to the accuracy of the
//                      refinement and the reflected one does not (face, feet, chest against back);
//   orientation  o_k = MapOrientation over the samples' triangles (orientation.h), near 1 for the
//                      right map and lower for a map that reflects the thin limbs.
// score_k = d_k + (1 - o_k) / 4; the term adds weight * (score_k - min score) to the refined
// candidates, so that it orders them and leaves the others as they were. The orientation counts
// half: on the sample triangles it is the noisier of the two (on TOSCA it ranked the oracle's
// candidate below its front-back partner on 10 pairs, the disagreement on 3), and with
// (1 - o_k) / 2 the synthetic humanoid of configs/quickstart.yaml gets one front-back flip.
// Measured on TOSCA (configs/tosca_paper.yaml, base): with weight 10 the mean error goes from
// 0.098 to 0.080 and the flipped pairs from 13 to 2; weights 3 and 30 give 0.086 and 0.080.
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>

#include "core/spectral.h"
#include "registry/types.h"

namespace symembed {

struct RefinedAgreementOptions {
  int k_start = 20;    // ZoomOut basis sizes (both bases need k_end eigenpairs)
  int k_end = 60;
  int step = 5;
  // Source samples the ZoomOut iterations run on and the measurement uses, and the target samples
  // they map to: the refinement maps the samples only, and the measurement compares them.
  int samples = 1000;
  int target_samples = 1000;
  int candidates = 2;  // candidates refined: the best by the other terms
  // Weight of the embedded surfaces' normals in the initial nearest-neighbour maps
  // (stages/matching/nearest.h): without them the map of a thin part mixes its two sides, and
  // ZoomOut from k_start cannot tell which side is which.
  double normal_weight = 0.1;

  bool IsValid(std::string* error) const;
};

struct RefinedScores {
  std::array<double, 4> total{};
  // NaN for the candidates that were not refined.
  std::array<double, 4> disagreement{};
  std::array<double, 4> orientation{};
};

// Adds the term to `scores` (the other terms' totals) for the best options.candidates
// candidates, each refined from the nearest-neighbour map of the shapes' embedded points
// (EmbeddedShape, the target turned by the candidate's rotation) with normals. The shapes'
// samples give the source samples (the first options.samples) and the target samples (the first
// options.target_samples). Fs, Ft: kExtrinsicFeaturesKey features. Throws ConfigError for
// invalid options, InvalidInputError for inputs that do not match.
RefinedScores AddRefinedTerm(const std::array<double, 4>& scores, double weight,
                             const ShapeData& source, const ShapeData& target,
                             const LaplaceBasis& source_basis, const LaplaceBasis& target_basis,
                             const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft,
                             const RefinedAgreementOptions& options);

}  // namespace symembed

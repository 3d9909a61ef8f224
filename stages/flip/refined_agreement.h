// Refined front-back decision of the flip stage (decide.type refined_front_back): decides
// between the best candidate by the terms and its front-back partner by how well their maps
// agree with the surfaces once ZoomOut has made them accurate.
//
// On a human, the candidate maps of the right rotation and of the rotation by pi about the
// vertical axis differ by a front-back reflection composed with the left-right one. The
// canonical embedding is thin front to back, so the nearest-neighbour maps carry almost no
// front-back information, and the short ZoomOut of the orientation term (orientation.h), which
// starts at a few eigenfunctions where a human's front and back look alike, can settle either
// candidate on a front-back reflection. This term takes the best candidate b by the other terms
// and its partner p = FrontBackPartner(b), the candidate turned by pi about the vertical axis,
// refines both maps with ZoomOut [Melzi et al. 2019] on the source samples, from a basis size at
// which the two are still apart (k_start 20), and measures each refined map of the samples twice:
//   disagreement d_k = FeatureDisagreement of the shape index and curvedness over the samples
//                      (extrinsic.h), which the right map preserves to the accuracy of the
//                      refinement and the reflected one does not (face, feet, chest against back);
//   orientation  o_k = MapOrientation over the samples' triangles (orientation.h), near 1 for the
//                      right map and lower for a map that reflects the thin limbs.
// score_k = d_k + (1 - o_k) / 4. The partner replaces b when score_b - score_p >= margin; the
// other terms keep deciding up and down. The orientation counts half: on the sample triangles it
// is the noisier of the two.
//
// Why a decision with a margin and not a weighted sum with the other terms: where the orientation
// term is confidently wrong (a human pose whose first eigenfunctions do not tell front from back)
// no weight of a sum lets the refined maps overrule it, and where front and back have nearly the
// same curvature (the synthetic humanoids) small score differences are noise that a sum lets
// overrule the right choice. The margin lies between the score differences of the two cases
// (docs/analysis.md, "Measurements behind the defaults").
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/fmap/zoomout.h"
#include "core/matching/deformed.h"
#include "core/spectral.h"
#include "registry/types.h"
#include "stages/flip/orientation.h"
#include "stages/flip/zoomout_schedule.h"

namespace symembed {

struct RefinedAgreementOptions {
  // ZoomOut basis sizes (both bases need k_end eigenpairs), the source samples the iterations run
  // on and the measurement uses, and the target samples they map to: the refinement maps the
  // samples only, and the measurement compares them.
  FlipZoomOutSchedule zoomout{/*k_start=*/20, /*k_end=*/60, /*step=*/5, /*samples=*/1000,
                              /*target_samples=*/1000};
  // How much lower the partner's score must be for it to replace the best candidate.
  double margin = 0.05;
  static constexpr Range kMargin = Range::AtLeast(0.0);
  // Weight of the embedded surfaces' normals in the initial nearest-neighbour maps
  // (core/matching/nearest.h): without them the map of a thin part mixes its two sides, and
  // ZoomOut from k_start cannot tell which side is which.
  double normal_weight = 0.1;
  static constexpr Range kNormalWeight = Range::AtLeast(0.0);

  // The options as the config names them (core/range.h), besides the `zoomout` map.
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("margin", self.margin, kMargin);
    visit("normal_weight", self.normal_weight, kNormalWeight);
  }
  bool IsValid(std::string* error) const;
};

// What refining a candidate's map needs that does not depend on the candidate, built once per
// pair: the source samples (the first schedule.samples) and the target samples they map onto,
// ZoomOut's setup, the embedded points of the source samples (ZoomOut reads the initial map at the
// samples only) and of the target, and the triangles and normals of the orientation
// (orientation.h). The shapes and bases are referenced: they must outlive it. Throws
// InvalidInputError for too few samples (`what` names the part in the message).
class RefinedCandidates {
 public:
  // With `deform`, each candidate's initial map is that of the `deformed` matching stage
  // (core/matching/deformed.h): the source embedding bent onto the turned target's before the
  // nearest neighbours; the source basis needs deform->k_end eigenpairs.
  RefinedCandidates(const ShapeData& source, const ShapeData& target,
                    const LaplaceBasis& source_basis, const LaplaceBasis& target_basis,
                    const FlipZoomOutSchedule& schedule, double normal_weight,
                    const std::string& what, const DeformOptions* deform = nullptr);

  // Candidate k's map: nearest neighbours of the embedded points with normals (as the matching
  // stage computes them, the target turned by CandidateRotations()[k]; the source bent first
  // with `deform`) on the samples, refined by ZoomOut. Only the samples' entries of the result
  // are meaningful.
  ZoomOutResult Refine(int k) const;
  // The orientation of a refined map on the samples' triangles.
  double Orientation(const std::vector<int>& map) const;
  const std::vector<int>& samples() const { return prefix_; }

 private:
  const ShapeData& source_;
  const ShapeData& target_;
  const LaplaceBasis& source_basis_;
  double normal_weight_;
  std::optional<DeformOptions> deform_;
  EmbeddedPoints source_all_;
  std::vector<int> prefix_;
  std::vector<int> target_prefix_;
  std::unique_ptr<ZoomOutSetup> zoomout_;
  EmbeddedPoints source_points_;
  EmbeddedPoints target_points_;
  SourceTriangles triangles_;
  Eigen::MatrixX3d target_normals_;
};

// The candidate turned from candidate k by pi about the vertical axis (y of the canonical frame):
// I <-> Ry, Rx <-> Rz in CandidateRotations() order.
inline constexpr int FrontBackPartner(int k) { return k ^ 2; }

struct RefinedChoice {
  int best = 0;     // argmin of the other terms' scores
  int partner = 0;  // FrontBackPartner(best)
  int chosen = 0;   // partner when score[best] - score[partner] >= margin, else best
  // NaN for the two candidates that were not refined.
  std::array<double, 4> disagreement{};
  std::array<double, 4> orientation{};
  std::array<double, 4> score{};
};

// Refines and scores the best candidate by `scores` (the other terms' totals; first on ties) and
// its partner, each from the nearest-neighbour map of the shapes' embedded points (EmbeddedShape,
// the target turned by the candidate's rotation) with normals. The shapes' samples give the
// source samples (the first options.zoomout.samples) and the target samples (the first
// options.zoomout.target_samples; every target vertex when it is 0). Fs, Ft:
// ExtrinsicFeatures. Throws ConfigError for invalid options, InvalidInputError for
// inputs that do not match.
RefinedChoice RefinedFrontBackChoice(const std::array<double, 4>& scores,
                                     const ShapeData& source, const ShapeData& target,
                                     const LaplaceBasis& source_basis,
                                     const LaplaceBasis& target_basis, const Eigen::MatrixXd& Fs,
                                     const Eigen::MatrixXd& Ft,
                                     const RefinedAgreementOptions& options);

}  // namespace symembed

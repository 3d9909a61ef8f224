// Refined-maps term of the flip stage `extrinsic`: how well each candidate's map, once refined,
// preserves the surfaces' intrinsic geometry, their curvature and their orientation.
//
// The curvature, descriptor and orientation terms compare the two shapes through features that
// change with the species, the body shape and the meshing. A wrong rotation, though, maps the
// head onto the tail or the back onto the belly, and no refinement from there gives a map that
// preserves distances along the surface, while the right rotation's map after ZoomOut [Melzi et
// al. 2019] preserves them up to the pair's non-isometry. For each candidate k the term takes the
// map the matching stage would start from (with deformed_start, the source embedding bent onto
// the turned target's, core/matching/deformed.h, then the nearest neighbours of the embedded
// points with normals, core/matching/nearest.h) on the source samples, refines it with ZoomOut
// on the samples, and measures three things of the refined map T of the samples:
//   distortion g_k   = sum_ij |d_S(s_i, s_j) - d_T(T(s_i), T(s_j))| / sum_ij d_S(s_i, s_j)
//                      over the first `sources` samples s_i and the first `targets` samples s_j,
//                      with graph geodesics (EdgeGraphDistances, core/mesh_graph.h) of the
//                      unit-area surfaces;
//   disagreement c_k = FeatureDisagreement of shape index and curvedness over the samples
//                      (extrinsic.h): on a human the candidate turned by pi about the vertical
//                      axis refines to a map that preserves distances about as well as the right
//                      one (front and back reflected), but puts the face on the back of the head
//                      and the chest on the back;
//   orientation o_k  = the orientation of the map on the samples' triangles (orientation.h): the
//                      left-right mirrored map preserves distances and curvature but reverses it.
// The bend matters where the two embeddings differ by more than the parts' size (a pose that
// LS-MDS keeps, a body of other proportions, an uneven meshing): the plain nearest neighbours of
// the right candidate then mix parts, ZoomOut from them settles on a poor map, and the term would
// judge the right rotation by it.
// And a fourth of the pair of candidates that share the direction of the long axis y of the
// canonical frame (k and p = FrontBackPartner(k), refined_agreement.h):
//   long axis   a_k  = min(C_k, C_p), C_k the FeatureDisagreement over the samples of the
//                      features diffused by heat for long_axis_time (DiffuseFeatures,
//                      extrinsic.h).
// Which end of the long axis is which (a human's head and feet, a quadruped's head and tail) shows
// in the body's shape at a scale that heat diffusion keeps, and there the diffused features do
// not depend on the meshing; the per-vertex curvature of c_k does, and on two independently
// decimated meshes its noise compresses the margin between the right map and a head-to-tail one.
// The partner swaps the two sides of the short in-plane axis: a quadruped's back and belly, which
// c_k and g_k tell apart, and a human's front and back, which differ only in details (face,
// chest, toes) that diffusion removes; so a_k scores both partners alike, by the better of their
// two maps (how well that direction of the long axis can be mapped: a quadruped's back-belly swap
// would otherwise count against its right direction), and leaves the choice between them to the
// other measures.
// Between k and its partner p the curvature decides by a vote of the samples:
//   front-back vote v_k = FeatureVote (extrinsic.h) of k's refined map against p's, in [-1, 1]:
//                      the share of the samples' area at which k's map puts each sample on a
//                      point of more alike curvature than p's, less the share where p's does.
// Where the two meshings differ (independent, uneven decimation) the per-vertex curvature has
// outliers of either sign, and c_k's mean moves with a few of them, while a human's front and
// back differ by details over many samples: the vote counts them and not how far off each is.
// With front_back_vote > 0 the curvature enters as c'_k = min(c_k, c_p)
// + front_back_vote max(0, -v_k): the partners share their lower mean disagreement (which, like
// g'_k, speaks to the long axis and the plane), and the one the samples vote against pays the
// margin it lost by. The winner's c'_k does not depend on the vote, so the vote decides between
// the partners and nothing else: not the direction of the long axis, not the plane hypotheses.
// It adds weight * (distortion_weight g'_k + disagreement_weight c'_k
// + orientation_weight (1 - o_k) + long_axis_weight a_k) to candidate k's total, where g'_k is
// min(g_k, g_p), or g_k with distortion_front_back: a human's partner is the right map reflected
// front to back, which preserves distances about as well, so there g_k's difference between the
// partners is noise beside c_k's; the lower of the two, like a_k, keeps the right plane's best
// total where the flip stage compares two symmetry planes. The four measure different failures,
// so none needs a threshold: each is a mean over the samples of a quantity near 0 for the right
// map. One ratio rules candidates out: a_k reads curvature at the body's ends, which an uneven
// meshing or a body of other proportions can turn, so where one pair's lower distortion g' is
// at least distortion_decides times the other pair's, the distances decide the long axis: the
// worse pair's totals are set above the other pair's, each by its distortion gap (weight
// distortion_weight), so both keep their order and a later term or the decision still sees them.
// The pairs' distortions either lie close (a_k decides) or several times apart, and the ratio
// sits between (docs/failure-modes.md, "The long axis by the distances"). The source's geodesics
// from its first `sources` samples are a per-shape product (AddNeeds), with the curvature features;
// the target's geodesics are computed per candidate from the images of the samples. [Bronstein,
// Bronstein & Kimmel 2006] Generalized multidimensional scaling (distortion of a map as the
// criterion of a correspondence).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "core/mesh.h"
#include "core/mesh_graph.h"
#include "registry/options.h"
#include "stages/flip/flip_term.h"
#include "stages/flip/zoomout_schedule.h"

namespace symembed {

struct RefinedMapsTermOptions {
  FlipZoomOutSchedule zoomout{/*k_start=*/20, /*k_end=*/60, /*step=*/5, /*samples=*/1000,
                              /*target_samples=*/1000};
  int sources = 40;  // samples the geodesics start from (on the target: their images)
  static constexpr Range kSources = Range::Closed(1, 100000);
  // Samples whose distances to the sources are compared (>= sources, <= zoomout.samples).
  int targets = 200;
  static constexpr Range kTargets = Range::Closed(1, 100000);
  // The curvature disagreement carries the front-back decision of near-symmetric humans, the
  // distortion the head-tail and up-down decisions of shapes whose curvature differs (species,
  // body shapes); the orientation of a refined map can favour a front-back reflected map on a
  // body whose front and back are alike, so it only breaks near ties.
  double distortion_weight = 0.5;
  // Whether g_k scores each candidate alone (true) or, like a_k, the pair of the candidate and its
  // front-back partner (false: the lower of their two distortions), so that it decides the long
  // axis only.
  bool distortion_front_back = false;
  double disagreement_weight = 1.0;
  double orientation_weight = 0.025;
  // The weight of the front-back vote v_k in c'_k (0: c_k itself, each candidate alone).
  double front_back_vote = 0.5;
  // Of the long-axis measure, and the heat diffusion time of its features (relative to the
  // area; an extent of about a third of sqrt(area) at 0.03: the body's scale).
  double long_axis_weight = 1.0;
  // Of distortion_weight, disagreement_weight, orientation_weight and long_axis_weight.
  static constexpr Range kWeight = Range::AtLeast(0.0);
  double long_axis_time = 0.03;
  static constexpr Range kLongAxisTime = Range::Above(0.0);
  // When one pair of front-back partners' lower distortion is at least this many times the other
  // pair's, that pair is ruled out (0: never; at most 1: the distortions alone decide the long
  // axis): the direction of the long axis is then the one whose maps keep distances that much
  // better, whatever a_k and c'_k say.
  double distortion_decides = 2.0;
  static constexpr Range kDistortionDecides = Range::AtLeast(0.0);
  // Of the curvature features (ExtrinsicFeatures, extrinsic.h).
  FeatureSmoothing smoothing = {};
  // Weight of the embedded normals in the initial maps (RefinedAgreementOptions::normal_weight).
  double normal_weight = 0.1;
  static constexpr Range kNormalWeight = Range::AtLeast(0.0);
  // Whether each candidate's initial map bends the source embedding onto the turned target's
  // first, as the `deformed` matching stage does with its defaults (core/matching/deformed.h),
  // so that the candidates are judged from the maps the pipeline would start from.
  bool deformed_start = true;

  // The options as the config names them (core/range.h), besides the `zoomout` map.
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("sources", self.sources, kSources);
    visit("targets", self.targets, kTargets);
    visit("distortion_weight", self.distortion_weight, kWeight);
    visit("distortion_front_back", self.distortion_front_back);
    visit("disagreement_weight", self.disagreement_weight, kWeight);
    visit("orientation_weight", self.orientation_weight, kWeight);
    visit("front_back_vote", self.front_back_vote, kWeight);
    visit("long_axis_weight", self.long_axis_weight, kWeight);
    visit("long_axis_time", self.long_axis_time, kLongAxisTime);
    visit("distortion_decides", self.distortion_decides, kDistortionDecides);
    FeatureSmoothing::Fields(self.smoothing, visit);
    visit("normal_weight", self.normal_weight, kNormalWeight);
    visit("deformed_start", self.deformed_start);
  }
  bool IsValid(std::string* error) const;
};

// The distortion d of `map` (target vertex per source vertex, at least at the samples) between
// the first sources.size() x targets samples: source_distances is #sources x #Vs (graph
// geodesics from samples[0..sources)), the target's are computed from the images on the target's
// edge graph (BuildMeshGraph). Returns 1 when the source distances sum to 0. Throws
// InvalidInputError for ids out of range.
double GeodesicDistortion(const Eigen::MatrixXd& source_distances, const MeshGraph& target,
                          const std::vector<int>& samples, int targets,
                          const std::vector<int>& map);

class RefinedMapsTerm : public FlipTerm {
 public:
  // Throws ConfigError for invalid options.
  RefinedMapsTerm(double weight, const RefinedMapsTermOptions& options);
  void AddNeeds(int stage_basis, ShapeNeeds* needs) const override;
  std::optional<FeatureSmoothing> Features() const override { return options_.smoothing; }
  int BasisSize() const override;
  void Score(const FlipTermContext& context, std::array<double, 4>* total,
             std::ostringstream* detail) const override;

 private:
  RefinedMapsTermOptions options_;
};

// The term of weight `weight` from its YAML map {zoomout, sources, targets, distortion_weight,
// distortion_front_back, disagreement_weight, orientation_weight, front_back_vote,
// long_axis_weight, long_axis_time, normal_weight, smoothing_rings, smoothing_radius} (defaults:
// RefinedMapsTermOptions). Throws ConfigError.
std::unique_ptr<FlipTerm> ReadRefinedMapsTerm(OptionReader& options, double weight);

}  // namespace symembed

// The paper's flip scorer: resolves the four-fold ambiguity of the canonical frame by comparing
// extrinsic surface features (shape index, curvedness) of the original surfaces.
//
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence: front and back, top
// and bottom are told apart by global and local extrinsic characteristics such as curvature.
// [Koenderink & van Doorn 1992] Surface shape and curvature scales (shape index, curvedness).
// For each candidate rotation R_k of the target (canonical frames, y up-down, z front-back):
//   local_k  = sum_v a_v mean_f |F_s(v, f) - F_t(T_k(v), f)| / sigma_f, T_k the nearest-neighbour
//              map source -> rotated target, a_v source area fractions, sigma_f the pooled
//              standard deviation of feature f;
//   global_k = for the y and z axes: L1 distance of the area profiles along the axis, plus the
//              L1 distances of the shape-index histograms of the two halves (u > 0, u < 0) and
//              the differences of their mean curvedness / sigma;
//   score_k  = local_weight * local_k + global_weight * global_k
//              + chamfer_weight * symmetric Chamfer distance of the embeddings.
// It is the curvature term of the flip stage `extrinsic` (term_curvature.h), to which the stage
// adds its other terms and a decision (extrinsic_stage.h).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/range.h"
#include "registry/options.h"
#include "stages/flip/flip_common.h"

namespace symembed {

// The neighbourhood the curvature features are averaged over (core/curvature.h): each vertex's
// `rings` rings, or, when radius > 0, the vertices within edge-graph distance radius * sqrt(total
// area). A number of rings is a size in edges, so it follows the meshing: two meshings of one
// surface, or one with elongated triangles, give each vertex neighbourhoods of other sizes and
// shapes, and the features differ where the surfaces do not. A radius is a size on the surface.
struct FeatureSmoothing {
  int rings = 2;
  static constexpr Range kRings = Range::Closed(0, 100);
  double radius = 0.0;  // > 0 overrides rings
  static constexpr Range kRadius = Range::AtLeast(0.0);

  // The options as a term's config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("smoothing_rings", self.rings, kRings);
    visit("smoothing_radius", self.radius, kRadius);
  }
  bool IsValid(std::string* error) const { return NoViolation(FieldViolation(*this), error); }
};

struct ExtrinsicFlipOptions {
  // Weights of the local, global and Chamfer scores (at least one > 0).
  double local_weight = 1.0;
  double global_weight = 1.0;
  double chamfer_weight = 0.0;
  static constexpr Range kWeight = Range::AtLeast(0.0);
  // Bins of the area profiles along y and z (over [-2, 2] RMS radii).
  int profile_bins = 16;
  // Bins of the shape-index histograms of each half.
  int histogram_bins = 8;
  static constexpr Range kBins = Range::Closed(1, 1000);
  // Averaging of the curvatures against noise (FeatureSmoothing): the paper's scorer over 2 rings.
  FeatureSmoothing smoothing = {};

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("local_weight", self.local_weight, kWeight);
    visit("global_weight", self.global_weight, kWeight);
    visit("chamfer_weight", self.chamfer_weight, kWeight);
    visit("profile_bins", self.profile_bins, kBins);
    visit("histogram_bins", self.histogram_bins, kBins);
    FeatureSmoothing::Fields(self.smoothing, visit);
  }
  bool IsValid(std::string* error) const;
};

// Per-candidate terms; total = weighted sum (see above).
struct ExtrinsicScores {
  std::array<double, 4> local{}, global{}, chamfer{}, total{};
};

// Ys, Yt: #Vs x 3, #Vt x 3 canonical embeddings; Fs, Ft: #V x 3 features (ExtrinsicFeatures
// layout); maps: ComputeCandidateMaps(Ys, Yt) (the stage shares them with the orientation
// term); threads: of the Chamfer distances. Throws ConfigError for invalid options,
// InvalidInputError on mismatched shapes.
ExtrinsicScores ExtrinsicFlipScores(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                    const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft,
                                    const ExtrinsicFlipOptions& options,
                                    const CandidateMaps& maps, int threads = 1);

// Scales of the shape index and curvedness columns for comparing Fs with Ft: the mean of the two
// shapes' area-weighted standard deviations (at least 1e-6).
std::array<double, 2> FeatureScales(const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft);

// sum_v a_v mean_f |Fs(v, f) - Ft(map[v], f)| / scales[f] over the shape index and curvedness,
// a_v the source area fractions: the `local` term of a map (#Vs target vertex ids). Given
// `vertices`, the sum runs over those source vertices only, a_v their share of their area.
double FeatureDisagreement(const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft,
                           const std::vector<int>& map, const std::array<double, 2>& scales,
                           const std::vector<int>& vertices = {});

// The vote of the source `vertices` between two maps (#Vs target vertex ids each): each vertex
// votes for the map under which its features differ less from its image's (the per-vertex
// quantity FeatureDisagreement averages), with its area a_v; returns
// sum_v a_v sign(e_b(v) - e_a(v)) / sum_v a_v in [-1, 1], positive when `a` wins. A median-like
// comparison: a few vertices whose curvature an uneven meshing has made noisy move the mean
// disagreement of a map but not the vote. Throws InvalidInputError when `vertices` is empty.
double FeatureVote(const Eigen::MatrixXd& Fs, const Eigen::MatrixXd& Ft, const std::vector<int>& a,
                   const std::vector<int>& b, const std::array<double, 2>& scales,
                   const std::vector<int>& vertices);

// The curvature features of `surface`, #V x 3 columns [shape index in [-1, 1],
// log(1 + curvedness * sqrt(area)), vertex area / total area], from core/curvature.h with
// curvatures averaged and fitted over the neighbourhoods of `smoothing`. Curvedness
// sqrt((k1^2 + k2^2) / 2) [Koenderink & van Doorn 1992] is made scale-free by sqrt(total area).
Eigen::MatrixXd ExtrinsicFeatures(const Surface& surface, const FeatureSmoothing& smoothing);

// The features F (#V x 3, ExtrinsicFeatures layout) of `surface` with the shape index and
// curvedness columns diffused by heat for the time `time` * total area: one implicit Euler step
// (M + time A K) f' = M f of the cotangent stiffness K and lumped mass M (core/laplacian.h), which
// keeps constants and the area-weighted mean of each column; the area column is kept. A diffusion
// time is an extent on the surface (about sqrt(4 time) of sqrt(area)), and the Laplacian converges
// under refinement, so two meshings of one surface, whose per-vertex estimates differ by the size
// and shape of each vertex's neighbourhood, get diffused features that agree where the raw ones
// do not; what is left is the body's shape at that scale. Throws ConfigError for a time that is
// not > 0 and finite, InvalidInputError when F does not match the surface or the system cannot
// be factored.
Eigen::MatrixXd DiffuseFeatures(const Surface& surface, const Eigen::MatrixXd& F, double time);

}  // namespace symembed

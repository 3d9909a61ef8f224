// Symmetry stage `plane2d`: the global reflectional symmetry detected in a 2D embedding and
// lifted to a plane in the 3D embedding.
//
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence: a 2D LS-MDS
// embedding of the samples' geodesic distances flattens the shape so that its intrinsic
// reflectional symmetry becomes a mirror line, robustly to pose and missing parts.
//   1. 2D embedding: classical MDS of the sample distances, refined by SMACOF
//      [de Leeuw 1977] (core/mds/smacof.h).
//   2. Coarse sweep of num_angles line directions through the centroid; each refined by
//      reflect / NN / refit iterations with a trimmed score (reflection_search.h).
//   3. Lift: the 3D reflection that best maps y_i to y_sigma(i) for the 2D self map sigma
//      (weighted by its confidence). The 3D embedding keeps much of the pose (it starts from the
//      surface's coordinates), so it may be far from symmetric: sigma stays the 2D one, and the
//      symmetrize stage makes the embedding symmetric under it.
//   4. Intrinsic check: a symmetry's self map preserves geodesic distances. Candidates are every
//      refined line with its 2D sigma, the same line refined for refine_3d_iterations in 3D
//      (sigma = 3D nearest neighbours), and, with candidates_3d, the plane3d candidates; the one
//      minimising score + intrinsic_weight * distortion wins. The 2D embedding of a shape with
//      many limbs can fold (a quadruped's legs overlap in 2D), where the 3D search does better;
//      the intrinsic check decides per shape.
//   5. Spectral check (spectral_symmetry.h): the winner's self map should commute with the low
//      Laplace-Beltrami eigenfunctions. When its SpectralConsistency is below
//      spectral.min_consistency (by default always), self maps from sign flips of the
//      eigenfunctions join the candidates (lifted like the 2D ones, scored by the lifted plane's
//      fit in 3D) and the criterion adds spectral.weight * (1 - consistency). Geodesic distances
//      alone cannot be trusted to pick the left-right symmetry: a quadruped has an approximate
//      front-back one (front legs to hind legs) and a near-identity one (back to belly across a
//      thin body) whose self maps distort distances as little, and a body bent so that one side
//      is compressed favours a front-back self map; the eigenfunctions still show the left-right
//      symmetry. The weight is small because the sign-flip self maps are coarse (nearest
//      neighbours in 8 dimensions): where a distance-based candidate of the same symmetry
//      exists, its better fit should win.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "registry/types.h"
#include "stages/symmetry/reflection_search.h"
#include "stages/symmetry/spectral_symmetry.h"

namespace symembed {

struct Plane2dOptions {
  ReflectionSearchOptions search;
  // Line directions of the coarse sweep over [0, pi).
  int num_angles = 36;
  static constexpr Range kNumAngles = Range::Closed(1, 3600);
  IntrinsicCheckOptions intrinsic;
  // SMACOF iterations of the 2D embedding (0: classical MDS only).
  int smacof_iterations = 200;
  static constexpr Range kSmacofIterations = Range::AtLeast(0);
  // Reflect / NN / refit iterations on the 3D embedding after the lift (0: no such candidates).
  int refine_3d_iterations = 10;
  static constexpr Range kRefine3dIterations = Range::AtLeast(0);
  // Also consider the plane3d candidates (principal axes and a sphere of normals in 3D).
  bool candidates_3d = true;
  // Starting normals of those candidates besides the principal axes.
  int num_directions = 32;
  static constexpr Range kNumDirections = Range::Closed(0, 10000);
  // Spectral candidates and check (step 5).
  SpectralSymmetryOptions spectral;
  // Candidates whose self map moves the samples less than this (the mean distance in the 3D
  // embedding between a sample and its image over the samples' RMS radius, as
  // `self_map_displacement` of shapes.csv) lose to every candidate that moves them more; 0: off.
  // A self map near the identity pairs samples on one side of the body, and the symmetrization
  // then presses the body into the plane.
  double min_self_map_displacement = 0.0;
  static constexpr Range kMinSelfMapDisplacement = Range::Closed(0.0, 10.0);
  // When the chosen self map moves the samples less than this, the stage also proposes the best
  // candidate that moves them at least this much as a second plane hypothesis (SymmetryStage::
  // RunAlternative), and each pair chooses between the shape's two planes by its flip score;
  // 0: off. Unlike min_self_map_displacement it decides nothing for the shape alone.
  double second_plane_below = 0.4;
  static constexpr Range kSecondPlaneBelow = Range::Closed(0.0, 10.0);
  // When the chosen self map moves the samples at least second_plane_below, the candidate of
  // the lowest criterion among those that move them at least 1.5 times as much is proposed as
  // the second plane hypothesis when its criterion is at most this factor times the chosen
  // one's: a near tie (a human's front-back self map keeps each limb on itself and can keep
  // distances as well as the left-right one, which swaps them). 1, or second_plane_below 0: off.
  double second_plane_tie = 1.25;
  static constexpr Range kSecondPlaneTie = Range::AtLeast(1.0);
  // > 0: each sample's confidence (the weight of its symmetry term in the symmetrize stage) is
  // multiplied by how well its self map keeps geodesic distances (DistanceConsistencyWeights
  // with this scale) and rescaled to the mean it had; 0: off.
  double distance_confidence = 0.0;
  static constexpr Range kDistanceConfidence = Range::AtLeast(0.0);
  // Threads of the 2D embedding's SMACOF and of the refinement of the line directions and of the
  // 3D candidates (0: all cores). The result does not depend on it.
  int threads = 0;
  static constexpr Range kThreads = Range::Closed(0, 256);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    ReflectionSearchOptions::Fields(self.search, visit);
    visit("num_angles", self.num_angles, kNumAngles);
    IntrinsicCheckOptions::Fields(self.intrinsic, visit);
    visit("smacof_iterations", self.smacof_iterations, kSmacofIterations);
    visit("min_self_map_displacement", self.min_self_map_displacement, kMinSelfMapDisplacement);
    visit("second_plane_below", self.second_plane_below, kSecondPlaneBelow);
    visit("second_plane_tie", self.second_plane_tie, kSecondPlaneTie);
    visit("refine_3d_iterations", self.refine_3d_iterations, kRefine3dIterations);
    visit("candidates_3d", self.candidates_3d);
    visit("num_directions", self.num_directions, kNumDirections);
    SpectralSymmetryOptions::Fields(self.spectral, visit);
    // Off unless given, so that the resolved options, and every cache key, stay as without it.
    visit("distance_confidence", self.distance_confidence, kDistanceConfidence, kIfGiven);
    visit("threads", self.threads, kThreads);
  }
  bool IsValid(std::string* error) const {
    return search.IsValid(error) && NoViolation(FieldViolation(*this), error);
  }
};

// Per sample i, how well the self map keeps its geodesic distances: d_i, the median over the
// anchors a (the first min(#S, 128) samples; farthest-point samples spread over the shape) of
// |Dss(i, a) - Dss(sigma(i), sigma(a))|, and the weight 1 / (1 + (d_i / (scale * median_i
// d_i))^2). A sample the self map sends to the wrong part of the body has distances to the
// anchors' images unlike its own, and a sample paired right has them alike up to the shape's own
// asymmetry, so the weights single out the wrong pairs without a threshold. All ones when every
// d_i is 0 (an exact symmetry). Dss: #S x #S sample distances; sigma: #S sample indices; scale >
// 0. Throws InvalidInputError when sigma does not match Dss or an index is out of range.
Eigen::VectorXd DistanceConsistencyWeights(const Eigen::MatrixXd& Dss,
                                           const std::vector<int>& sigma, double scale);

// The 2D embedding of step 1: Dss #S x #S symmetric distances -> #S x 2 (centred). SMACOF runs on
// `threads` threads (0: all cores); its result does not depend on them.
Eigen::MatrixXd EmbedSamples2d(const Eigen::MatrixXd& Dss, int smacof_iterations, int threads);

// The mean distance between each sample's point in Y (#V x 3) and its image's under sigma (#S,
// sample indices), over the samples' RMS radius: how far the self map moves the samples
// (SelfMapDisplacement of core/procrustes.h). Throws InvalidInputError when sigma does not match
// the samples or a sample id is out of range.
double SampleSelfMapDisplacement(const Eigen::MatrixXd& Y, const std::vector<int>& samples,
                                 const std::vector<int>& sigma);

// The candidates of one detection, steps 1 to 4, which do not depend on
// min_self_map_displacement (their arguments as DetectSymmetryPlane2d's, which throws the same).
class Plane2dCandidates;
std::shared_ptr<const Plane2dCandidates> SearchPlane2d(
    const Eigen::MatrixXd& D, const std::vector<int>& samples, const Eigen::MatrixXd& Y,
    const Plane2dOptions& options, const Eigen::MatrixXd& G = Eigen::MatrixXd(),
    const Eigen::VectorXd& evals = Eigen::VectorXd());
// Step 5 and the choice among the candidates with the given min_self_map_displacement (the
// search's own options otherwise): DetectSymmetryPlane2d's result for options with that bound,
// bit for bit, without searching again (the symmetry stage's second plane).
SymmetryResult ChoosePlane2d(const Plane2dCandidates& candidates, double min_self_map_displacement);

// D: #S x #V geodesic distances from the samples; samples: #S >= 4 vertex ids; Y: #V x 3
// embedding; G: #S x K spectral coordinates of the samples (SampleSpectralCoordinates), or empty
// to leave out step 5; evals: their K eigenvalues (or empty: each eigenfunction checked on its
// own). Returns the plane in the coordinates of Y, the sample self map, per-sample
// confidence and the score of the chosen candidate (in its space). Throws InvalidInputError on
// inconsistent shapes, ConfigError on invalid options.
SymmetryResult DetectSymmetryPlane2d(const Eigen::MatrixXd& D, const std::vector<int>& samples,
                                     const Eigen::MatrixXd& Y, const Plane2dOptions& options,
                                     const Eigen::MatrixXd& G = Eigen::MatrixXd(),
                                     const Eigen::VectorXd& evals = Eigen::VectorXd());

}  // namespace symembed

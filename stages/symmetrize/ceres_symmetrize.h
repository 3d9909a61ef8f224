// Symmetrize stage `ceres`: deform the 3D embedding so that it becomes symmetric about its
// symmetry plane while keeping its shape.
//
// With the plane moved to x = 0 (MovePlaneToX0) and sample positions x_i (#S x 3) as unknowns,
// stress majorization from y, then Ceres' Levenberg-Marquardt (max_iterations), lower (all
// residuals divided by the size s of the sample set, so weights are scale-free)
//   sum_{(i,j) in kNN graph} (||x_i - x_j|| - d0_ij)^2                     shape (stress)
// + symmetry_weight * sum_i c_i ||M x_i - m_i||^2, M = diag(-1,1,1)         symmetry
// + plane_weight * sum_{i: sigma(i) = i} x_i,x^2        self-symmetric samples (mirror_neighbors 1)
// + anchor_weight * sum_i ||x_i - y_i||^2                                 (optional, off)
// where d0_ij = ||y_i - y_j|| in the unsymmetrized embedding, the graph is the symmetric k-NN
// graph of the samples there, and c_i the symmetry confidence. m_i is the mirror counterpart of
// sample i: x_sigma(i) when mirror_neighbors = 1 (the design's formula, the default), otherwise,
// where sigma(i) is among the mirror_neighbors samples nearest to M y_i, an affine combination
// sum_j w_ij x_j of those samples with locally linear reconstruction weights
// [Roweis & Saul 2000] (elsewhere x_sigma(i)). Forcing M x_i onto a single mirror sample
// drags the surface by up to half the sample spacing wherever the samples are not themselves
// placed symmetrically (farthest point sampling never is); the combination reproduces the
// mirror point between samples instead. Started from y. Dense vertices follow the samples
// (FollowSamples). With combinations, a sample whose nearest mirror sample is itself is not
// necessarily on the plane (coarse sampling), so the plane term applies only with
// mirror_neighbors = 1; otherwise the symmetry term already holds samples near the plane on it.
// Asymmetry is reported before and after (hard sigma, SymmetrizeResult) and, in the message,
// the mirror residual of the combinations (MirrorResidual).
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence;
// [Agarwal et al.] Ceres Solver.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "core/range.h"
#include "registry/types.h"
#include "stages/symmetrize/stress_majorization.h"

namespace symembed {

struct CeresSymmetrizeOptions {
  // Weight of the symmetry term relative to the stress term. Strong by default: what the
  // embedding keeps of an asymmetric pose (one arm raised, the head turned) differs between two
  // poses of a body, and pulling each embedding onto its mirror image removes it, at the price
  // of some distortion where sigma is not a bijection (docs/analysis.md compares 1, 3 and 10).
  double symmetry_weight = 10.0;
  // Weight keeping self-symmetric samples (sigma(i) = i) on the plane (mirror_neighbors = 1).
  double plane_weight = 10.0;
  // Weight pulling samples to their unsymmetrized positions (0: off).
  double anchor_weight = 0.0;
  // Of symmetry_weight, plane_weight and anchor_weight.
  static constexpr Range kWeight = Range::AtLeast(0.0);
  // Neighbours per sample in the stress graph.
  int graph_neighbors = 16;
  static constexpr Range kGraphNeighbors = Range::Closed(1, 1000);
  // Samples combined into each mirror counterpart (1: x_sigma(i) itself, the default: sigma may
  // come from intrinsic information that the 3D embedding, which keeps part of the pose, does
  // not show; combinations fit only embeddings that are nearly symmetric already).
  int mirror_neighbors = 1;
  static constexpr Range kMirrorNeighbors = Range::Closed(1, 64);
  // Nearest samples whose displacements a dense vertex follows.
  int follow_neighbors = 8;
  static constexpr Range kFollowNeighbors = Range::Closed(1, 1000);
  // Stress-majorization iterations started from y before the Ceres solve (0: none), and their
  // stop: an iteration lowering the energy by less than this fraction (stress_majorization.h).
  // Levenberg-Marquardt alone crawls on this energy; the majorization iterations, each cheap,
  // bring it close to the minimum and the Ceres iterations after them polish
  // (docs/analysis.md, "Measurements behind the defaults").
  int warm_start_iterations = 1000;
  static constexpr Range kWarmStartIterations = Range::AtLeast(0);
  double warm_start_tolerance = 1e-6;
  static constexpr Range kWarmStartTolerance = Range::AtLeast(0.0);
  // Levenberg-Marquardt iterations of Ceres after the majorization (0: none, the majorization's
  // positions are the result and Ceres is not called). Stopping there lowered the base error on
  // every set but moved the refined maps of a few SMAL pairs (docs/analysis.md).
  int max_iterations = 10;
  static constexpr Range kMaxIterations = Range::AtLeast(0);
  double function_tolerance = 1e-7;
  static constexpr Range kFunctionTolerance = Range::Above(0.0);
  int threads = 1;
  static constexpr Range kThreads = Range::Closed(1, 256);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("symmetry_weight", self.symmetry_weight, kWeight);
    visit("plane_weight", self.plane_weight, kWeight);
    visit("anchor_weight", self.anchor_weight, kWeight);
    visit("graph_neighbors", self.graph_neighbors, kGraphNeighbors);
    visit("mirror_neighbors", self.mirror_neighbors, kMirrorNeighbors);
    visit("follow_neighbors", self.follow_neighbors, kFollowNeighbors);
    visit("max_iterations", self.max_iterations, kMaxIterations);
    visit("function_tolerance", self.function_tolerance, kFunctionTolerance);
    visit("threads", self.threads, kThreads);
    visit("warm_start_iterations", self.warm_start_iterations, kWarmStartIterations);
    visit("warm_start_tolerance", self.warm_start_tolerance, kWarmStartTolerance);
  }
  bool IsValid(std::string* error) const { return NoViolation(FieldViolation(*this), error); }
};

// Y: #V x 3 embedding; samples: #S ids; symmetry: plane in Y's coordinates, sigma (#S),
// confidence (#S, or empty = all 1). Returns #V x 3 symmetric about x = 0. Throws
// InvalidInputError on inconsistent input, ConfigError on invalid options.
SymmetrizeResult SymmetrizeCeres(const Eigen::MatrixXd& Y, const std::vector<int>& samples,
                                 const SymmetryResult& symmetry,
                                 const CeresSymmetrizeOptions& options);

// The stage's energy (above, before the common 1 / size^2 factor) of the samples P (#S x 3,
// plane x = 0) with symmetry's sigma and confidence (#S, or empty = all 1): the terms the warm
// start minimises and the Ceres problem is built from.
SymmetrizeEnergy CeresSymmetrizeEnergy(const Eigen::MatrixX3d& P, const SymmetryResult& symmetry,
                                       const CeresSymmetrizeOptions& options);

// Relative stress of sample positions X against the reference P on P's symmetric k-NN graph:
// sqrt(sum (||x_i - x_j|| - ||p_i - p_j||)^2 / sum ||p_i - p_j||^2). P, X: #S x 3.
double GraphStress(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& X, int k);

// Mirror counterparts as weighted samples: out[i] = {(j, w_ij)}, weights summing to 1, from the
// positions P (#S x 3, plane x = 0). k = 1: {(sigma[i], 1)}.
std::vector<std::vector<std::pair<int, double>>> MirrorWeights(const Eigen::MatrixX3d& P,
                                                               const std::vector<int>& sigma,
                                                               int k);

// mean_i ||M x_i - sum_j w_ij x_j|| / size with the weights of MirrorWeights (computed on other
// positions): how far the reflected samples are from their counterparts. X: #S x 3.
double MirrorResidual(const Eigen::MatrixX3d& X,
                      const std::vector<std::vector<std::pair<int, double>>>& weights);

// The symmetric k-NN graph of P (#S x 3) as pairs i < j.
std::vector<std::pair<int, int>> KnnGraphEdges(const Eigen::MatrixX3d& P, int k);

}  // namespace symembed

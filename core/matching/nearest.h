// The matching stages `nearest` and `nearest_scaled` (stages/matching/register.cpp):
// correspondence as the nearest neighbour in the aligned embeddings.
//
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence: once both
// embeddings are in the canonical frame and the flip is resolved, each source vertex maps to the
// nearest target vertex (FLANN kd-tree, exact). `nearest_scaled` first aligns the source to the
// target up to a per-axis scale and a translation by ICP [Besl & McKay 1992], which absorbs
// non-isometric stretch (e.g. longer limbs) that the canonical frame keeps.
//
// Sides of thin parts: the nearest target point of a point on a thin part of the embedded surface
// (a limb, an ear, a flat torso) may lie on the other side of the part, a few embedding units
// away but half the part's circumference away on the surface. With normal_weight w > 0 both
// stages match in R^6, points (y, w r n) with n the unit normal of the embedded surface and r
// the target's RMS radius: squared distance |y - y'|^2 + (w r)^2 |n - n'|^2, so a point whose
// normal points the other way is 2 w r further away. The embedded surfaces are consistently
// oriented and the candidate rotation is proper, so the normals of corresponding points agree.
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/matching/match.h"
#include "core/range.h"

namespace symembed {

// Ys: #Vs x 3 source, Yt: #Vt x 3 target (rotated). map[i] = nearest target vertex of source i.
// Throws InvalidInputError for empty or non-finite inputs.
MatchResult MatchNearest(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt, int threads = 0);

// The same with the normals weighted by normal_weight (>= 0; 0: positions only, normals may
// then be empty). Throws InvalidInputError when normal_weight > 0 and the normals do not match
// the points (rows) or are not finite; ConfigError for a negative weight.
MatchResult MatchNearest(const EmbeddedPoints& source, const EmbeddedPoints& target,
                         double normal_weight, int threads = 0);

// Default normal_weight of both stages.
inline constexpr double kDefaultNormalWeight = 0.1;

struct ScaledIcpOptions {
  // ICP iterations (NN, then per-axis scale and translation by least squares).
  int iterations = 10;
  static constexpr Range kIterations = Range::Closed(0, 1000);
  // Use pairs in both directions (source -> target and target -> source); one direction alone
  // can shrink the source onto part of the target.
  bool symmetric = true;
  // Per-axis scales are clamped to [min_scale, max_scale].
  double min_scale = 0.5;
  static constexpr Range kMinScale = Range::Closed(1e-3, 1.0);
  double max_scale = 2.0;
  static constexpr Range kMaxScale = Range::Closed(1.0, 1e3);
  // Weight of the normals in the final nearest-neighbour match (MatchNearest above); the ICP
  // itself uses the positions. The normals follow the per-axis scale (n / s, renormalised).
  double normal_weight = kDefaultNormalWeight;
  static constexpr Range kNormalWeight = Range::AtLeast(0.0);
  // Threads of the NN queries (0: DefaultThreadCount()).
  int threads = 0;
  static constexpr Range kThreads = Range::Closed(0, 256);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("iterations", self.iterations, kIterations);
    visit("symmetric", self.symmetric);
    visit("min_scale", self.min_scale, kMinScale);
    visit("max_scale", self.max_scale, kMaxScale);
    visit("normal_weight", self.normal_weight, kNormalWeight);
    visit("threads", self.threads, kThreads);
  }
  bool IsValid(std::string* error) const { return NoViolation(FieldViolation(*this), error); }
};

// Per-axis scale s and translation b with the source moved to y -> s .* y + b, found by ICP.
struct ScaledAlignment {
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  int iterations = 0;
};

ScaledAlignment AlignScaled(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                            const ScaledIcpOptions& options);

// AlignScaled, then MatchNearest of the moved source.
MatchResult MatchNearestScaled(const EmbeddedPoints& source, const EmbeddedPoints& target,
                               const ScaledIcpOptions& options,
                               ScaledAlignment* alignment = nullptr);

}  // namespace symembed

// Matching stages `nearest` and `nearest_scaled`: correspondence as the nearest neighbour in the
// aligned embeddings.
//
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence: once both
// embeddings are in the canonical frame and the flip is resolved, each source vertex maps to the
// nearest target vertex (FLANN kd-tree, exact). `nearest_scaled` first aligns the source to the
// target up to a per-axis scale and a translation by ICP [Besl & McKay 1992], which absorbs
// non-isometric stretch (e.g. longer limbs) that the canonical frame keeps.
#pragma once

#include <Eigen/Core>
#include <string>

#include "registry/types.h"

namespace symembed {

// Ys: #Vs x 3 source, Yt: #Vt x 3 target (rotated). map[i] = nearest target vertex of source i.
// Throws InvalidInputError for empty or non-finite inputs.
MatchResult MatchNearest(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt, int threads = 0);

struct ScaledIcpOptions {
  // ICP iterations (NN, then per-axis scale and translation by least squares).
  int iterations = 10;
  // Use pairs in both directions (source -> target and target -> source); one direction alone
  // can shrink the source onto part of the target.
  bool symmetric = true;
  // Per-axis scales are clamped to [min_scale, max_scale].
  double min_scale = 0.5;
  double max_scale = 2.0;
  // Threads of the NN queries (0: DefaultThreadCount()).
  int threads = 0;

  bool IsValid(std::string* error) const;
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
MatchResult MatchNearestScaled(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                               const ScaledIcpOptions& options,
                               ScaledAlignment* alignment = nullptr);

}  // namespace symembed

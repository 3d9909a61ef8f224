// What the matching algorithms compare and return: points of an embedding with the normals of
// the embedded surface, and a vertex map with its solver status.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/stage_status.h"

namespace symembed {

// Points of an embedding to match: positions Y (#P x 3) and the unit normals N of the embedded
// surface at them (#P x 3, rotated with Y; empty when not available).
struct EmbeddedPoints {
  Eigen::MatrixX3d Y;
  Eigen::MatrixX3d N;
};

// Points and normals rotated by R (y' = R y for every row y).
EmbeddedPoints Rotated(const EmbeddedPoints& points, const Eigen::Matrix3d& R);

struct MatchResult {
  std::vector<int> map;  // #V_source: target vertex of each source vertex
  StageStatus status;
};

}  // namespace symembed

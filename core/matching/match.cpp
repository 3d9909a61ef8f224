#include "core/matching/match.h"

namespace symembed {

EmbeddedPoints Rotated(const EmbeddedPoints& points, const Eigen::Matrix3d& R) {
  return {points.Y * R.transpose(), points.N * R.transpose()};
}

}  // namespace symembed

#include "registry/types.h"

namespace symembed {

std::array<Eigen::Matrix3d, 4> CandidateRotations() {
  return {Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix(),
          Eigen::Vector3d(-1, 1, -1).asDiagonal().toDenseMatrix(),
          Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix()};
}

}  // namespace symembed

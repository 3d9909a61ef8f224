#include "registry/types.h"

#include "core/laplacian.h"

namespace symembed {

std::array<Eigen::Matrix3d, 4> CandidateRotations() {
  return {Eigen::Matrix3d::Identity(), Eigen::Vector3d(1, -1, -1).asDiagonal().toDenseMatrix(),
          Eigen::Vector3d(-1, 1, -1).asDiagonal().toDenseMatrix(),
          Eigen::Vector3d(-1, -1, 1).asDiagonal().toDenseMatrix()};
}

EmbeddedPoints EmbeddedShape(const ShapeData& shape, const Eigen::Matrix3d& R) {
  return Rotated(EmbeddedPoints{shape.Y, VertexNormals(shape.Y, shape.surface.F)}, R);
}

}  // namespace symembed

#include <cmath>

#include "core/curvature.h"
#include "core/errors.h"
#include "core/laplacian.h"
#include "stages/flip/extrinsic.h"

namespace symembed {

Eigen::MatrixXd ExtrinsicFeatures(const Surface& surface, const FeatureSmoothing& smoothing) {
  if (surface.NumVertices() == 0 || surface.NumFaces() == 0) {
    throw InvalidInputError("flip extrinsic: empty surface");
  }
  CurvatureOptions options;
  options.smoothing_rings = smoothing.rings;
  options.smoothing_radius = smoothing.radius;
  const CurvatureFeatures c = ComputeCurvature(surface, options);
  const Eigen::VectorXd areas = VertexAreas(surface);
  const double total = areas.sum();
  if (!(total > 0.0)) throw InvalidInputError("flip extrinsic: surface of zero area");
  const double unit = std::sqrt(total);
  Eigen::MatrixXd F(surface.NumVertices(), 3);
  F.col(0) = c.shape_index;
  const Eigen::ArrayXd curvedness = ((c.k1.array().square() + c.k2.array().square()) / 2.0).sqrt();
  F.col(1) = (1.0 + curvedness * unit).log().matrix();
  F.col(2) = areas / total;
  return F;
}

}  // namespace symembed

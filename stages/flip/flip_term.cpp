#include "stages/flip/flip_term.h"

#include "stages/flip/extrinsic.h"

namespace symembed {

ProductKey<Eigen::MatrixXd> CurvatureFeaturesKey(int smoothing_rings) {
  return {"curvature_features", "smoothing_rings=" + std::to_string(smoothing_rings)};
}

ProductNeed CurvatureFeaturesNeed(int smoothing_rings) {
  return NeedProduct(CurvatureFeaturesKey(smoothing_rings), ProductInput::kSurface, 0,
                     [smoothing_rings](const ShapeData& shape, const LaplaceBasis&) {
                       return ExtrinsicFeatures(shape.surface, smoothing_rings);
                     });
}

}  // namespace symembed

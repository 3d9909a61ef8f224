#include "stages/flip/flip_term.h"

#include <sstream>

#include "stages/flip/extrinsic.h"

namespace symembed {

ProductKey<Eigen::MatrixXd> CurvatureFeaturesKey(const FeatureSmoothing& smoothing) {
  // The key names only the smoothing in use: ring smoothing keeps its `smoothing_rings=N`
  // text, so cached features over rings stay valid whatever radius options exist.
  if (smoothing.radius <= 0.0) {
    return {"curvature_features", "smoothing_rings=" + std::to_string(smoothing.rings)};
  }
  std::ostringstream text;
  text.precision(17);
  text << "smoothing_radius=" << smoothing.radius;
  return {"curvature_features", text.str()};
}

ProductNeed CurvatureFeaturesNeed(const FeatureSmoothing& smoothing) {
  return NeedProduct(CurvatureFeaturesKey(smoothing), ProductInput::kSurface, 0,
                     [smoothing](const ShapeData& shape, const LaplaceBasis&) {
                       return ExtrinsicFeatures(shape.surface, smoothing);
                     });
}

ProductKey<Eigen::MatrixXd> DiffusedFeaturesKey(const FeatureSmoothing& smoothing, double time) {
  std::ostringstream text;
  text.precision(17);
  text << CurvatureFeaturesKey(smoothing).options << " diffusion_time=" << time;
  return {"diffused_features", text.str()};
}

ProductNeed DiffusedFeaturesNeed(const FeatureSmoothing& smoothing, double time) {
  return NeedProduct(DiffusedFeaturesKey(smoothing, time), ProductInput::kSurface, 0,
                     [smoothing, time](const ShapeData& shape, const LaplaceBasis&) {
                       return DiffuseFeatures(shape.surface,
                                              ExtrinsicFeatures(shape.surface, smoothing), time);
                     });
}

}  // namespace symembed

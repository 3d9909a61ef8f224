// The curvature term of the flip stage `extrinsic`, pipeline.flip.terms.curvature: the paper's
// scorer, curvature features compared locally through each candidate's nearest-neighbour map and
// globally along the canonical axes (extrinsic.h), times the term's weight.
//   curvature: {weight: 1, local_weight: 1, global_weight: 1, chamfer_weight: 0,
//               profile_bins: 16, histogram_bins: 8, smoothing_rings: 2, smoothing_radius: 0}
// Per shape it needs the curvature features (CurvatureFeaturesKey), which the refined decision
// (decide_refined.h) reads too. Status message: "; local l0 l1 l2 l3; global g0 g1 g2 g3".
#pragma once

#include <memory>

#include "registry/options.h"
#include "stages/flip/extrinsic.h"
#include "stages/flip/flip_term.h"

namespace symembed {

class CurvatureTerm : public FlipTerm {
 public:
  // Throws ConfigError for invalid options.
  CurvatureTerm(double weight, const ExtrinsicFlipOptions& options);
  void AddNeeds(int stage_basis, ShapeNeeds* needs) const override;
  std::optional<FeatureSmoothing> Features() const override { return options_.smoothing; }
  // Needs the context's features.
  void Score(const FlipTermContext& context, std::array<double, 4>* total,
             std::ostringstream* detail) const override;
  const ExtrinsicFlipOptions& options() const { return options_; }

 private:
  ExtrinsicFlipOptions options_;
};

// The term from its options besides `weight` (read by the stage). Throws ConfigError.
std::unique_ptr<FlipTerm> ReadCurvatureTerm(OptionReader& options, double weight);

}  // namespace symembed

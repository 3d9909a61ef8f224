// The decision `refined_front_back` of the flip stage `extrinsic`, pipeline.flip.decide: the
// candidate with the lowest total, unless its front-back partner's refined map agrees better with
// the surfaces by at least `margin` (refined_agreement.h).
//   decide: {type: refined_front_back, margin: 0.05, normal_weight: 0.1,
//            zoomout: {k_start: 20, k_end: 60, step: 5, samples: 1000, target_samples: 1000}}
// It reads the curvature features, which the curvature term prepares. Status message:
// "; refined d0/o0 d1/o1 d2/o2 d3/o3" (disagreement / orientation, "-" for a candidate not
// refined), then "; refined maps choose P over B (score s_P against s_B)" when the partner wins.
#pragma once

#include <memory>

#include "registry/options.h"
#include "stages/flip/flip_term.h"
#include "stages/flip/refined_agreement.h"

namespace symembed {

class RefinedDecision : public FlipDecision {
 public:
  // Throws ConfigError for invalid options.
  explicit RefinedDecision(const RefinedAgreementOptions& options);
  int BasisSize() const override { return options_.zoomout.k_end; }
  bool ReadsFeatures() const override { return true; }
  int Decide(const FlipTermContext& context, const std::array<double, 4>& total,
             std::ostringstream* detail) const override;
  const RefinedAgreementOptions& options() const { return options_; }

 private:
  RefinedAgreementOptions options_;
};

// The decision from its options besides `type` (read by the stage). Throws ConfigError.
std::unique_ptr<FlipDecision> ReadRefinedDecision(OptionReader& options);

}  // namespace symembed

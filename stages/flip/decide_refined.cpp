#include "stages/flip/decide_refined.h"

#include <cmath>

#include "core/errors.h"

namespace symembed {

RefinedDecision::RefinedDecision(const RefinedAgreementOptions& options) : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw ConfigError("flip refined: " + error);
}

int RefinedDecision::Decide(const FlipTermContext& context, const std::array<double, 4>& total,
                            std::ostringstream* detail) const {
  SYMEMBED_CHECK(context.source_features && context.target_features,
                 "the refined decision needs the features in its context");
  const RefinedChoice refined = RefinedFrontBackChoice(
      total, context.pair.source, context.pair.target, context.source_basis,
      context.target_basis, *context.source_features, *context.target_features, options_);
  *detail << "; refined";
  for (int k = 0; k < 4; ++k) {
    if (std::isnan(refined.disagreement[k])) *detail << " -";
    else *detail << " " << refined.disagreement[k] << "/" << refined.orientation[k];
  }
  if (refined.chosen != refined.best) {
    *detail << "; refined maps choose " << kCandidateNames[refined.chosen] << " over "
            << kCandidateNames[refined.best] << " (score " << refined.score[refined.chosen]
            << " against " << refined.score[refined.best] << ")";
  }
  return refined.chosen;
}

std::unique_ptr<FlipDecision> ReadRefinedDecision(OptionReader& o) {
  RefinedAgreementOptions f;
  ReadFields(o, &f);
  f.zoomout = ReadFlipZoomOutSchedule(o, "zoomout", f.zoomout);
  RequireValid(o, f);
  return std::make_unique<RefinedDecision>(f);
}

}  // namespace symembed

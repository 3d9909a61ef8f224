#include "stages/flip/term_curvature.h"

#include "core/errors.h"

namespace symembed {

CurvatureTerm::CurvatureTerm(double weight, const ExtrinsicFlipOptions& options)
    : FlipTerm(weight), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw ConfigError("flip curvature: " + error);
}

void CurvatureTerm::AddNeeds(int, ShapeNeeds* needs) const {
  needs->products.push_back(CurvatureFeaturesNeed(options_.smoothing));
}

void CurvatureTerm::Score(const FlipTermContext& context, std::array<double, 4>* total,
                          std::ostringstream* detail) const {
  SYMEMBED_CHECK(context.source_features && context.target_features,
                 "the curvature term needs the features in its context");
  const ExtrinsicScores s =
      ExtrinsicFlipScores(context.pair.source.Y, context.pair.target.Y, *context.source_features,
                          *context.target_features, options_, context.maps, context.threads);
  // With weight 1 the totals are the paper's scores bit for bit: multiplying by 1 is exact, and
  // adding x to the stage's initial +0 gives x (the scores are sums of non-negative products, so
  // never -0).
  for (int k = 0; k < 4; ++k) (*total)[k] += weight() * s.total[k];
  *detail << "; local";
  for (double v : s.local) *detail << " " << v;
  *detail << "; global";
  for (double v : s.global) *detail << " " << v;
}

std::unique_ptr<FlipTerm> ReadCurvatureTerm(OptionReader& o, double weight) {
  ExtrinsicFlipOptions e;
  ReadValidFields(o, &e);
  return std::make_unique<CurvatureTerm>(weight, e);
}

}  // namespace symembed

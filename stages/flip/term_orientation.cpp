#include "stages/flip/term_orientation.h"

#include <cmath>

#include "core/errors.h"

namespace symembed {

OrientationTerm::OrientationTerm(double weight, const OrientationOptions& options)
    : FlipTerm(weight), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw ConfigError("flip orientation: " + error);
}

void OrientationTerm::Score(const FlipTermContext& context, std::array<double, 4>* total,
                            std::ostringstream* detail) const {
  const PairInput& pair = context.pair;
  const CandidateOrientation measure(pair.source.surface, pair.target.surface,
                                     context.source_basis, context.target_basis,
                                     pair.source.samples, pair.target.samples, options_);
  const OrientationScores scores = AddOrientationTerm(*total, weight(), context.maps, measure);
  *total = scores.total;
  *detail << "; orientation";
  for (double v : scores.orientation) {
    if (std::isnan(v)) *detail << " -";
    else *detail << " " << v;
  }
}

std::unique_ptr<FlipTerm> ReadOrientationTerm(OptionReader& o, double weight) {
  OrientationOptions r;
  r.zoomout = ReadFlipZoomOutSchedule(o, "zoomout", r.zoomout);
  RequireValid(o, r);
  return std::make_unique<OrientationTerm>(weight, r);
}

}  // namespace symembed

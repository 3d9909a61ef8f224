// The orientation term of the flip stage `extrinsic`, pipeline.flip.terms.orientation: adds
// weight * (1 - o_k) / 2 for the orientation o_k of candidate k's map after a short ZoomOut
// (orientation.h), measuring only the candidates that can still have the lowest total
// (AddOrientationTerm).
//   orientation: {weight: 1, zoomout: {k_start: 6, k_end: 60, step: 5, samples: 200,
//                                      target_samples: 1000}}
// Status message: "; orientation o0 o1 o2 o3", "-" for a candidate not measured.
#pragma once

#include <memory>

#include "registry/options.h"
#include "stages/flip/flip_term.h"
#include "stages/flip/orientation.h"

namespace symembed {

class OrientationTerm : public FlipTerm {
 public:
  // Throws ConfigError for invalid options.
  OrientationTerm(double weight, const OrientationOptions& options);
  int BasisSize() const override { return options_.zoomout.k_end; }
  void Score(const FlipTermContext& context, std::array<double, 4>* total,
             std::ostringstream* detail) const override;
  const OrientationOptions& options() const { return options_; }

 private:
  OrientationOptions options_;
};

// The term from its options besides `weight` (read by the stage). Throws ConfigError.
std::unique_ptr<FlipTerm> ReadOrientationTerm(OptionReader& options, double weight);

}  // namespace symembed

// The flip stage `extrinsic`: a sum of terms per candidate rotation of the target (lower is
// better), then a decision. Its options (pipeline.flip, defaults shown):
//   type: extrinsic
//   threads: 1
//   terms:                                    # each term's weight 0 switches it off
//     curvature:    {weight: 0, ...}          # the paper's scorer (term_curvature.h)
//     descriptor:   {weight: 0, ...}          # wave kernel signature map (term_descriptor.h)
//     refined_maps: {weight: 1, ...}          # refined candidates' distortion, curvature
//                                             # disagreement and orientation
//                                             # (term_refined_maps.h)
//     orientation:  {weight: 0, zoomout: {...}}  # refined candidates' orientation
//                                             # (term_orientation.h)
//   decide: {type: argmin}                    # or {type: refined_front_back, ...}
//                                             # (decide_refined.h)
// The terms are added in this order; a term of weight 0 is validated but neither prepared nor
// computed, and at least one must be on. The paper's scorer alone is terms.curvature.weight 1,
// terms.refined_maps.weight 0 and decide.type argmin.
// Per shape the stage prepares the Laplace-Beltrami basis the parts need (the largest
// BasisSize()) and each term's data. Status message: "extrinsic scores [I, Rx, Ry, Rz]: ..."
// followed by each term's values and the decision's.
#pragma once

#include <memory>

#include "registry/options.h"
#include "registry/stages.h"

namespace symembed {

// The stage from its options (the reader of pipeline.flip). Throws ConfigError (file:line:col
// and dotted path) for unknown keys, values out of range, an unknown decision type, no term on,
// or a decision reading the curvature features with the curvature term off.
std::unique_ptr<FlipStage> ReadExtrinsicStage(OptionReader& options);

}  // namespace symembed

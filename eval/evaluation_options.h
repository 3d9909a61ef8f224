// The `evaluation` section of a config: how the evaluator measures a run's maps
// (eval/evaluator.h) and where the refine stage starts.
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

#include "registry/registry.h"

namespace symembed {

struct EvaluationOptions {
  std::string geodesics = "fast_marching";  // a registered geodesics type
  double max_error = 0.25;                  // right end of the cumulative curve
  double step = 0.0025;                     // curve resolution
  int points = 0;                           // 0 = all ground-truth points; N = N FPS points
  // Where the refine stage starts: "matching" (the matching stage's map) or "ground_truth" (the
  // pair's ground truth as a map), which measures how far a refinement drifts from the answer
  // it should keep; a pair without ground truth then fails.
  std::string refine_start = "matching";
};

// The `evaluation` section of a config (strict: unknown keys and bad values throw ConfigError
// naming file and key; a missing section gives the defaults). registry, when given, checks that
// `geodesics` names a registered type; reading back a resolved config.yaml needs none.
EvaluationOptions ParseEvaluationOptions(const YAML::Node& node, const std::string& file,
                                         const Registry* registry);

}  // namespace symembed

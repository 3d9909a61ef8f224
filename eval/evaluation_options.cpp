#include "eval/evaluation_options.h"

#include <cstdlib>

#include "registry/options.h"

namespace symembed {

EvaluationOptions ParseEvaluationOptions(const YAML::Node& node, const std::string& file,
                                         const Registry* registry) {
  OptionReader r(node, file, "evaluation");
  EvaluationOptions e;
  e.geodesics = registry != nullptr
                    ? r.GetChoice("geodesics", e.geodesics, registry->Names("geodesics"))
                    : r.GetString("geodesics", e.geodesics);
  e.max_error = r.GetDouble("max_error", e.max_error, Range::Closed(1e-6, 10.0));
  e.step = r.GetDouble("step", e.step, Range::Closed(1e-6, e.max_error));
  const std::string points = r.GetString("points", "all");
  if (points != "all") {
    char* end = nullptr;
    const long n = std::strtol(points.c_str(), &end, 10);
    if (points.empty() || *end != '\0' || n < 1 || n > 100000000) {
      r.Fail("points", "invalid value '" + points + "'; expected 'all' or a positive integer");
    }
    e.points = static_cast<int>(n);
  }
  e.refine_start = r.GetChoice("refine_start", e.refine_start, {"matching", "ground_truth"});
  r.Finish();
  return e;
}

}  // namespace symembed

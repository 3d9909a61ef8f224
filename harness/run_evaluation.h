// The evaluation behind `symembed run` and `symembed merge`: the runner's evaluation interfaces
// (harness/runner.h RunEvaluation) implemented with the evaluator (eval/evaluator.h) and its
// report writers (eval/report.h).
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "eval/evaluator.h"
#include "harness/runner.h"
#include "registry/registry.h"

namespace symembed {

// The evaluator's view of a computed shape: its preprocessed surface, with the input vertices
// removed by the preprocess looked up as in MakeEvalShape.
EvalShape EvalShapeOf(const ShapeOutcome& shape);

// Variants whose evaluation options and preprocess stage resolve alike share one Evaluator, so
// the distances it caches per target (the bulk of the evaluation's time) are computed once for
// all of them.
class GroundTruthRunEvaluation : public RunEvaluation {
 public:
  // registry: builds the evaluation geodesics of ForVariant (not needed by merge alone).
  explicit GroundTruthRunEvaluation(const Registry* registry = nullptr);
  ~GroundTruthRunEvaluation() override;

  std::unique_ptr<VariantEvaluation> ForVariant(const Pipeline& pipeline) override;
  // summary.json, pairs.csv, curve.csv, timings.csv from the records; a pair without a record
  // is reported failed with its message from failures.csv.
  void WriteVariant(const VariantResults& results) override;
  // comparison.csv and the plots.
  void WriteExperiment(const std::string& dir, const std::vector<std::string>& variants) override;

  // Problems that are not errors (a plot that could not be made), for the command to print.
  const std::vector<std::string>& warnings() const { return warnings_; }

  struct Shared;  // an Evaluator shared by variants (defined in the .cpp)

 private:
  const Registry* registry_;
  std::map<std::string, std::shared_ptr<Shared>> shared_;
  std::vector<std::string> warnings_;
};

}  // namespace symembed

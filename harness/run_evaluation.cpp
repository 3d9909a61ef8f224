#include "harness/run_evaluation.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <mutex>
#include <sstream>

#include "core/errors.h"
#include "core/files.h"
#include "eval/evaluator.h"
#include "eval/report.h"
#include "harness/config.h"
#include "registry/hash.h"

namespace symembed {

EvalShape EvalShapeOf(const ShapeOutcome& shape) {
  PreprocessResult pre;
  pre.surface = shape.data->surface;
  pre.input_ids = shape.data->input_ids;
  pre.scale = shape.data->scale;
  return MakeEvalShape(pre, shape.input);
}

namespace {

// The evaluator's distance cache budget: $SYMEMBED_EVAL_CACHE_MB, default
// kDefaultEvaluationCacheMb. Every target of TOSCA 5k with all ground-truth points needs about
// 100 MB; a budget that holds all of them lets the variants of a run share the distances instead
// of recomputing them per variant, at that cost in memory.
double EvaluationCacheBudgetMb() {
  const char* env = std::getenv("SYMEMBED_EVAL_CACHE_MB");
  if (env == nullptr || *env == '\0') return kDefaultEvaluationCacheMb;
  char* end = nullptr;
  const double mb = std::strtod(env, &end);
  if (end == env || *end != '\0' || !(mb >= 0.0)) {
    throw ConfigError(std::string("SYMEMBED_EVAL_CACHE_MB: expected a number of megabytes >= 0, "
                                  "got '") +
                      env + "'");
  }
  return mb;
}

}  // namespace

// An Evaluator with its own geodesics stage, and the evaluator's view of each target shape.
struct GroundTruthRunEvaluation::Shared {
  std::unique_ptr<GeodesicsStage> geodesics;
  std::unique_ptr<Evaluator> evaluator;
  std::mutex mutex;
  std::map<std::string, std::unique_ptr<EvalShape>> targets;  // by TargetId

  // The evaluator keeps each target's distances under the id it is given, and the variants of
  // one run may load different meshes under one name (a variant that remeshes the synthetic
  // set): the id is the name with the key of the shape's preprocessed surface (its mesh file's
  // content and the preprocessing), so that only the same surface shares distances.
  static std::string TargetId(const ShapeOutcome& shape) {
    return shape.name + "@" + HexDigest(shape.surface_key);
  }

  // The target's id and the evaluator's view of it.
  std::pair<std::string, const EvalShape*> Target(const ShapeOutcome& shape) {
    std::string id = TargetId(shape);
    std::lock_guard<std::mutex> lock(mutex);
    auto& slot = targets[id];
    if (!slot) slot = std::make_unique<EvalShape>(EvalShapeOf(shape));
    return {std::move(id), slot.get()};
  }
};

namespace {

class GroundTruthVariantEvaluation : public VariantEvaluation {
 public:
  using Shared = GroundTruthRunEvaluation::Shared;
  explicit GroundTruthVariantEvaluation(std::shared_ptr<Shared> shared)
      : shared_(std::move(shared)) {}

  double MeanError(const PairContext& pair, const std::vector<int>& predicted,
                   double* distance_seconds) const override {
    // A full-length map holding the predictions at the ground-truth source vertices.
    std::vector<int> map(pair.source.input.NumVertices(), 0);
    for (size_t i = 0; i < predicted.size(); ++i)
      map[pair.ground_truth.source_ids[i]] = predicted[i];
    const auto [id, target] = shared_->Target(pair.target);
    return shared_->evaluator->MeanError(id, *target, map, pair.ground_truth, distance_seconds);
  }

  PairEvaluation Evaluate(const PairContext& pair, const PairOutcome& outcome,
                          std::string* failure) const override {
    const auto [id, target] = shared_->Target(pair.target);
    PairEvaluation evaluation =
        shared_->evaluator->Evaluate(pair.source.name, id, *target, outcome.map, pair.ground_truth,
                                     outcome.flip.chosen, outcome.oracle);
    evaluation.target = pair.target.name;
    if (!evaluation.ok) {
      *failure = "evaluation: " + evaluation.message;
      return evaluation;
    }
    if (!outcome.initial_map.empty()) {
      const PairEvaluation initial =
          shared_->evaluator->Evaluate(pair.source.name, id, *target, outcome.initial_map,
                                       pair.ground_truth, outcome.flip.chosen, outcome.oracle);
      if (initial.ok) {
        evaluation.refined = true;
        evaluation.initial_mean_direct = initial.mean_direct;
        evaluation.initial_mean_sym = initial.mean_sym;
      }
    }
    for (const StageTime& t : outcome.times) evaluation.stage_seconds[t.stage] = t.seconds;
    const std::pair<const char*, const StageStatus*> statuses[] = {
        {"flip", &outcome.flip.status},
        {"matching", &outcome.matching_status},
        {"refine", &outcome.refine_status}};
    for (const auto& [stage, status] : statuses) {
      if (!status->message.empty()) evaluation.stage_messages[stage] = status->message;
    }
    if (outcome.oracle >= 0) {
      evaluation.candidate_errors.assign(outcome.oracle_errors.begin(),
                                         outcome.oracle_errors.end());
    }
    return evaluation;
  }

 private:
  std::shared_ptr<Shared> shared_;
};

}  // namespace

GroundTruthRunEvaluation::GroundTruthRunEvaluation(const Registry* registry)
    : registry_(registry) {}
GroundTruthRunEvaluation::~GroundTruthRunEvaluation() = default;

std::unique_ptr<VariantEvaluation> GroundTruthRunEvaluation::ForVariant(const Pipeline& pipeline) {
  SYMEMBED_CHECK(registry_ != nullptr, "GroundTruthRunEvaluation::ForVariant needs the registry");
  const EvaluationOptions& e = pipeline.evaluation;
  std::ostringstream key;
  key.precision(17);
  key << OptionsText(*pipeline.evaluation_geodesics) << "|" << e.max_error << "|" << e.step << "|"
      << e.points << "|" << OptionsText(*pipeline.preprocess);
  std::shared_ptr<Shared>& shared = shared_[key.str()];
  if (!shared) {
    shared = std::make_shared<Shared>();
    shared->geodesics = registry_->CreateAs<GeodesicsStage>(
        "geodesics", YAML::Clone(pipeline.evaluation_geodesics->resolved_options()), "",
        "evaluation.geodesics");
    shared->evaluator =
        std::make_unique<Evaluator>(e, *shared->geodesics, EvaluationCacheBudgetMb());
  }
  return std::make_unique<GroundTruthVariantEvaluation>(shared);
}

void GroundTruthRunEvaluation::WriteVariant(const VariantResults& results) {
  std::map<std::pair<std::string, std::string>, std::string> messages;
  for (const Failure& f : results.failures) {
    if (f.kind == "pair") messages.emplace(std::make_pair(f.source, f.target), f.message);
  }
  std::vector<PairEvaluation> pairs;
  for (size_t i = 0; i < results.pairs.size(); ++i) {
    const DatasetPair& p = results.pairs[i];
    if (results.records[i]) {
      pairs.push_back(*results.records[i]);
      continue;
    }
    PairEvaluation failed;
    failed.source = p.source;
    failed.target = p.target;
    auto it = messages.find({p.source, p.target});
    failed.message = it == messages.end() ? "failed" : it->second;
    pairs.push_back(std::move(failed));
  }
  VariantTimings timings;
  timings.total_seconds = results.wall_seconds;
  timings.peak_rss_mb = PeakRssMb();
  if (!results.merged_from.empty()) {
    // A merge: the shards' own totals (they ran elsewhere, possibly at the same time).
    timings.total_seconds = 0.0;
    timings.peak_rss_mb = 0.0;
    for (const std::string& shard : results.merged_from) {
      try {
        const VariantSummary s = ReadSummaryJson(shard + "/summary.json");
        timings.total_seconds += s.time_total_s;
        timings.peak_rss_mb = std::max(timings.peak_rss_mb, s.peak_rss_mb);
      } catch (const std::exception& e) {
        warnings_.push_back(shard + ": no timings (" + e.what() + ")");
      }
    }
  }
  for (const ShapeRecord& shape : results.shapes) {
    auto& stages = timings.shape_stage_seconds[shape.name];
    for (const StageTime& t : shape.times) stages[t.stage] = t.seconds;
  }
  const std::string config = VariantConfigPath(results.dir);
  const EvaluationOptions options =
      ParseEvaluationOptions(LoadConfigYaml(ReadFileOrThrow(config), config)["evaluation"],
                             config, registry_);
  VariantSummary summary = Summarize(results.variant, pairs, options, timings);
  summary.shapes_lost_area = 0;
  for (const ShapeRecord& shape : results.shapes) {
    for (const auto& [key, value] : shape.report) {
      if (key == "removed_component_area" && value > 0.0) ++summary.shapes_lost_area;
    }
  }
  if (summary.shapes_lost_area > 0) {
    warnings_.push_back(results.dir + ": preprocessing removed components of " +
                        std::to_string(summary.shapes_lost_area) +
                        " shapes (see removed_component_area in shapes.csv)");
  }
  WriteVariantOutputs(results.dir, summary, pairs, timings);
}

void GroundTruthRunEvaluation::WriteExperiment(const std::string& dir,
                                               const std::vector<std::string>& variants) {
  std::vector<VariantSummary> summaries;
  for (const std::string& name : variants) {
    const std::string path = dir + "/" + name + "/summary.json";
    if (std::filesystem::exists(path)) summaries.push_back(ReadSummaryJson(path));
  }
  std::string warning;
  if (!WriteComparison(dir, summaries, &warning) && !warning.empty()) warnings_.push_back(warning);
}

}  // namespace symembed

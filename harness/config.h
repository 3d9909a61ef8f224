// Experiment configuration: one YAML file = dataset + pipeline (one entry per stage kind) +
// evaluation + ablation variants (name + dotted-path overrides).
//
// Parsing is strict and complete before anything runs: every variant is resolved and every one
// of its stages instantiated, so unknown keys, wrong types, bad enum values, out-of-range
// numbers and missing required keys fail with `file:line:col`, the dotted path and what was
// expected. Strings may use ${VAR} and ${VAR:-default} (environment substitution).
//
//   name: tosca_paper
//   dataset: {format: pairs_vts, root: ${SYMEMBED_DATA:-../shared/data}/tosca_iso_5k}
//   pipeline:
//     embedding: {type: lsmds, dims: 3}
//   evaluation: {geodesics: fast_marching, max_error: 0.25, step: 0.0025, points: all}
//   variants:
//     - {name: isomap, set: {pipeline.embedding.type: isomap}}
//
// A variant that changes a stage's `type` starts that stage from the new type's defaults: the
// base's options for the old type are dropped unless the variant sets them again. The same holds
// for a nested `type` (pipeline.flip.decide.type) and the other keys of its map.
#pragma once

#include <yaml-cpp/yaml.h>

#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "eval/evaluation_options.h"
#include "registry/dataset.h"
#include "registry/registry.h"
#include "registry/stage_kinds.h"

namespace symembed {

// The instantiated stages of one variant.
struct Pipeline {
  std::unique_ptr<Dataset> dataset;
  // One member per stage kind, named by it: `std::unique_ptr<SymmetryStage> symmetry;`.
#define SYMEMBED_PIPELINE_MEMBER(name, Name, scope, default_type) std::unique_ptr<Name##Stage> name;
  SYMEMBED_STAGE_KINDS(SYMEMBED_PIPELINE_MEMBER)
#undef SYMEMBED_PIPELINE_MEMBER
  std::unique_ptr<GeodesicsStage> evaluation_geodesics;
  EvaluationOptions evaluation;

  // The stage of a pipeline kind ("sampling", ...).
  const Stage& StageOf(const std::string& kind) const;

  // Calls f(kind name, unique_ptr member) for each stage of pipeline (a Pipeline or a const
  // Pipeline), in the order of the stage kinds (registry/stage_kinds.h).
  template <typename P, typename F>
  static void ForEachStage(P& pipeline, F&& f) {
#define SYMEMBED_VISIT_STAGE(name, Name, scope, default_type) f(#name, pipeline.name);
    SYMEMBED_STAGE_KINDS(SYMEMBED_VISIT_STAGE)
#undef SYMEMBED_VISIT_STAGE
  }
};

struct VariantConfig {
  std::string name;  // "base" for the base pipeline
  YAML::Node tree;   // the whole config tree after overrides and substitution (no variants)
};

struct ExperimentConfig {
  std::string name;
  std::string description;
  std::string file;                     // where it was read from (for messages)
  std::vector<VariantConfig> variants;  // "base" first, then the file's variants in order
  // Per command-line override that a variant's own `set` replaces for that variant (the same
  // key, or one inside the other): the variant's name and a line naming both; the caller shows
  // them.
  std::vector<std::pair<std::string, std::string>> shadowed_overrides;
  const VariantConfig* Find(const std::string& variant) const;
  // The variant of that name; throws ConfigError naming the file and every variant otherwise.
  const VariantConfig& Get(const std::string& variant) const;
};

// Reads, substitutes, resolves and validates (instantiating every stage of every variant).
// Throws ConfigError (file:line:col, dotted path, expectation) or IoError.
// `overrides` ("dotted.path=value", as `symembed run --set`) apply to the base and to every
// variant, before the variant's own overrides (which win for the keys they set; see
// ExperimentConfig::shadowed_overrides). With `only_variant` the name of one of the config's
// variants (as `symembed run --variant`), only that variant is validated, so that an override
// of a stage only it selects (`--variant refined --set pipeline.refine.k_end=160` where the
// base has `refine: none`) need not fit the others; any other value validates every variant.
ExperimentConfig LoadExperimentConfig(const std::string& path, const Registry& registry,
                                      const std::vector<std::string>& overrides = {},
                                      const std::string& only_variant = "");
ExperimentConfig ParseExperimentConfig(const std::string& yaml_text, const std::string& file,
                                       const Registry& registry,
                                       const std::vector<std::string>& overrides = {},
                                       const std::string& only_variant = "");

// Instantiates the stages of one variant (throws ConfigError).
Pipeline BuildPipeline(const ExperimentConfig& config, const VariantConfig& variant,
                       const Registry& registry);

// The fully resolved config of a variant (every option with its default), as YAML text that
// ParseExperimentConfig reads back to the same pipeline.
std::string ResolvedConfigYaml(const ExperimentConfig& config, const VariantConfig& variant,
                               const Pipeline& pipeline);

// Parses YAML text as a config file is parsed: throws ConfigError naming file:line:col for a
// syntax error, for an alias inside the node it names (a recursive alias, which would make the
// tree infinite), and for text whose aliases expand to more than kMaxYamlNodes nodes (an alias
// bomb), before the tree is built.
constexpr long long kMaxYamlNodes = 1000000;
// Variants in one config (ParseExperimentConfig refuses more, naming the list).
constexpr size_t kMaxVariants = 10000;
YAML::Node LoadConfigYaml(const std::string& text, const std::string& file);

// Replaces ${VAR} and ${VAR:-default} in text; an unset VAR without default throws ConfigError
// naming `where`.
std::string ExpandEnvironment(const std::string& text, const std::string& where);

}  // namespace symembed

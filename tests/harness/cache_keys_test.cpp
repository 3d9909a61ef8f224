// The cache keys follow from the stage-kind table (registry/stage_kinds.h): every kind's
// options enter the keys of what it computes and of everything after it, so a kind added to the
// table is keyed without being named here.
#include <gtest/gtest.h>

#include <string>
#include <type_traits>
#include <vector>

#include "harness/config.h"
#include "harness/pair_pipeline.h"
#include "harness/shape_pipeline.h"
#include "registry/registry.h"
#include "registry/stage_kinds.h"

namespace symembed {
namespace {

const char* kKeysConfig = R"(name: keys
dataset: {format: synthetic, kinds: [humanoid], poses: 2}
)";

struct KeyedPipeline {
  Registry registry;
  ExperimentConfig config;
  Pipeline pipeline;
  KeyedPipeline() {
    RegisterBuiltinStages(registry);
    config = ParseExperimentConfig(kKeysConfig, "keys.yaml", registry);
    pipeline = BuildPipeline(config, config.variants[0], registry);
  }
};

// The pipeline's stage of a kind, to change its options.
Stage& MutableStageOf(Pipeline& pipeline, const std::string& kind) {
  Stage* found = nullptr;
  Pipeline::ForEachStage(pipeline, [&](const char* name, auto& stage) {
    if (kind == name) found = stage.get();
  });
  EXPECT_NE(found, nullptr) << kind;
  return *found;
}

ShapeOutcome KeyedShape(const std::string& name, uint64_t key) {
  ShapeOutcome shape;
  shape.name = name;
  shape.key = key;
  return shape;
}

// A per-shape kind's options change its output's key, every later per-shape key and the last
// (which the shape's pair-cache key starts from), not the earlier ones nor PairKey given the
// shapes' keys; a per-pair kind's options change PairKey and no shape key.
TEST(CacheKeys, EveryKindOfTheTableEntersTheKeys) {
  KeyedPipeline p;
  const uint64_t mesh_key = 12345;
  const ShapeOutcome source = KeyedShape("a", 1), target = KeyedShape("b", 2);
  const InputGroundTruth truth{{0, 1}, {1, 0}, {}};
  const ShapeStageKeys base(mesh_key, p.pipeline);
  const uint64_t base_pair = PairKey(source, target, p.pipeline, truth);
  int shape_kinds = 0, pair_kinds = 0;
  for (const StageKind& kind : kPipelineStageKinds) {
    Stage& stage = MutableStageOf(p.pipeline, kind.name);
    const YAML::Node original = YAML::Clone(stage.resolved_options());
    YAML::Node changed = YAML::Clone(original);
    changed["cache_keys_test"] = 1;
    stage.set_resolved_options(changed);
    const ShapeStageKeys keys(mesh_key, p.pipeline);
    const uint64_t pair = PairKey(source, target, p.pipeline, truth);
    stage.set_resolved_options(original);

    bool reached = false;  // kind or a per-shape kind after it
    for (const StageKind& other : kPipelineStageKinds) {
      if (other.scope != StageScope::kShape) continue;
      reached = reached || std::string(other.name) == kind.name;
      EXPECT_EQ(keys.Of(other.name) != base.Of(other.name), reached)
          << "options of " << kind.name << ", key of " << other.name;
    }
    if (kind.scope == StageScope::kShape) {
      ++shape_kinds;
      EXPECT_NE(keys.Last(), base.Last()) << kind.name;
      EXPECT_EQ(pair, base_pair) << kind.name << ": the shapes' keys carry it";
    } else {
      ++pair_kinds;
      EXPECT_EQ(keys.Last(), base.Last()) << kind.name;
      EXPECT_NE(pair, base_pair) << kind.name << "'s options are not in PairKey";
    }
  }
  EXPECT_GT(shape_kinds, 0);
  EXPECT_GT(pair_kinds, 0);
  // Unchanged options give the same keys.
  EXPECT_EQ(ShapeStageKeys(mesh_key, p.pipeline).Last(), base.Last());
  EXPECT_EQ(PairKey(source, target, p.pipeline, truth), base_pair);
}

// The rest of what PairKey holds: the shapes, the evaluation's geodesics and the ground truth.
TEST(CacheKeys, PairKeyHoldsTheShapesTheEvaluationAndTheGroundTruth) {
  KeyedPipeline p;
  const ShapeOutcome source = KeyedShape("a", 1), target = KeyedShape("b", 2);
  const InputGroundTruth truth{{0, 1}, {1, 0}, {}};
  const uint64_t base = PairKey(source, target, p.pipeline, truth);
  EXPECT_NE(PairKey(KeyedShape("a", 3), target, p.pipeline, truth), base);
  EXPECT_NE(PairKey(source, KeyedShape("c", 2), p.pipeline, truth), base);
  EXPECT_NE(PairKey(target, source, p.pipeline, truth), base);
  EXPECT_NE(PairKey(source, target, p.pipeline, InputGroundTruth{{0, 1}, {0, 1}, {}}), base);
  YAML::Node changed = YAML::Clone(p.pipeline.evaluation_geodesics->resolved_options());
  changed["cache_keys_test"] = 1;
  p.pipeline.evaluation_geodesics->set_resolved_options(changed);
  EXPECT_NE(PairKey(source, target, p.pipeline, truth), base);
}

// The table's scope of a kind and its interface agree: the per-pair kinds, whose options
// PairKey holds, are the PairStages, whose needs the shape pipeline gathers.
TEST(CacheKeys, PerPairKindsOfTheTableArePairStages) {
  Pipeline pipeline;
  std::vector<bool> pair_stage;
  Pipeline::ForEachStage(pipeline, [&](const char*, auto& stage) {
    using T = typename std::remove_reference_t<decltype(stage)>::element_type;
    pair_stage.push_back(std::is_base_of_v<PairStage, T>);
  });
  std::vector<bool> per_pair;
  for (const StageKind& kind : kPipelineStageKinds) {
    per_pair.push_back(kind.scope == StageScope::kPair);
  }
  EXPECT_EQ(pair_stage, per_pair);
}

}  // namespace
}  // namespace symembed

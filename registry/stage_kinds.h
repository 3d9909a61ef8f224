// The stage kinds: one row each (SYMEMBED_STAGE_KINDS), in pipeline order, with whether each
// runs per shape or per pair and its default type. The registry (which kinds may be
// registered), the config parser (which `pipeline` keys exist, the defaults of kinds a config
// leaves out), the resolved config, the pipeline builder, the cache keys (the per-shape rows in
// ShapeStageKeys, harness/shape_pipeline.h; the per-pair rows in PairKey,
// harness/pair_pipeline.h), the members of Pipeline and Pipeline::ForEachStage
// (harness/config.h), and the registration of the built-in stages (stages/register.h) all
// follow from the rows.
#pragma once

#include <string>
#include <vector>

namespace symembed {

enum class StageScope { kShape, kPair };

struct StageKind {
  const char* name;
  StageScope scope;
  const char* default_type;  // the built-in type used when a config does not name one
};

// The stage kinds, one row each, in pipeline order (the per-shape chain, then the per-pair
// chain): X(name, Name, scope, default type). `name` is the kind's key under `pipeline:`, its
// member of Pipeline (harness/config.h) and its folder stages/<name>/; `Name` names its
// interface <Name>Stage (registry/stages.h) and its registration function
// Register<Name>Stages (stages/register.h); the default type is the built-in type used when a
// config does not name one. Every list of the kinds in the code is expanded from these rows.
#define SYMEMBED_STAGE_KINDS(X)                   \
  X(preprocess, Preprocess, kShape, "standard")   \
  X(sampling, Sampling, kShape, "farthest_point") \
  X(geodesics, Geodesics, kShape, "dijkstra")     \
  X(embedding, Embedding, kShape, "lsmds")        \
  X(symmetry, Symmetry, kShape, "plane2d")        \
  X(symmetrize, Symmetrize, kShape, "ceres")      \
  X(flip, Flip, kPair, "extrinsic")               \
  X(matching, Matching, kPair, "deformed")        \
  X(refine, Refine, kPair, "none")

inline constexpr StageKind kPipelineStageKinds[] = {
#define SYMEMBED_STAGE_KIND_ROW(name, Name, scope, default_type) \
  {#name, StageScope::scope, default_type},
    SYMEMBED_STAGE_KINDS(SYMEMBED_STAGE_KIND_ROW)
#undef SYMEMBED_STAGE_KIND_ROW
};

// The kind of the dataset loaders, registered like stages but not part of the pipeline chain.
inline constexpr const char* kDatasetKind = "dataset";

// The names of kPipelineStageKinds, in order.
const std::vector<std::string>& PipelineKinds();
// PipelineKinds() then kDatasetKind: every kind the registry accepts.
const std::vector<std::string>& StageKinds();
// The default type of a pipeline kind; "" for any other name.
std::string DefaultStageType(const std::string& kind);

}  // namespace symembed

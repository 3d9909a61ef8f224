// The stage kinds: one table of their names, in pipeline order, with whether each runs per
// shape or per pair and its default type. The registry (which kinds may be registered), the
// config parser (which `pipeline` keys exist, the defaults of kinds a config leaves out), the
// resolved config, the pipeline builder and the cache keys (the per-shape rows in
// ShapeStageKeys, harness/shape_pipeline.h; the per-pair rows in PairKey,
// harness/pair_pipeline.h) all read it; the interface of each kind is in registry/stages.h and
// its member in Pipeline (harness/config.h), bound to the table by Pipeline::ForEachStage.
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

// Pipeline order: the per-shape chain, then the per-pair chain.
inline constexpr StageKind kPipelineStageKinds[] = {
    {"preprocess", StageScope::kShape, "standard"},
    {"sampling", StageScope::kShape, "farthest_point"},
    {"geodesics", StageScope::kShape, "dijkstra"},
    {"embedding", StageScope::kShape, "lsmds"},
    {"symmetry", StageScope::kShape, "plane2d"},
    {"symmetrize", StageScope::kShape, "ceres"},
    {"flip", StageScope::kPair, "extrinsic"},
    {"matching", StageScope::kPair, "deformed"},
    {"refine", StageScope::kPair, "none"},
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

// Per-pair work of one variant (docs/design.md, "Data flow"), source A -> target B:
//   flip scorer picks one of CandidateRotations() -> B's embedding rotated (y' = R y) ->
//   matching(Y_A, R Y_B) -> refine(pair, map) -> map in input vertex ids. With
//   `evaluation.refine_start: ground_truth` the refine stage starts from the ground truth
//   (MapFromGroundTruth) instead of the matching stage's map.
// Source input vertices removed by preprocessing take the map of the nearest kept source vertex;
// target ids are converted through the target's input_ids.
//
// The oracle candidate (when the dataset has ground truth): for each candidate rotation, only
// the ground-truth source points are matched by the matching stage, and the candidate with the
// lowest mean error (given by the caller, i.e. the evaluator) wins. It is what the flip scorer
// should have chosen, and classifies a wrong choice as front-back or up-down.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "harness/config.h"
#include "harness/shape_pipeline.h"

namespace symembed {

struct PairOutcome {
  std::vector<int> map;          // #V_source_input: 0-based target input id per source vertex
  std::vector<int> initial_map;  // the same before refinement; empty when refine kept the map
  FlipResult flip;               // scores and chosen candidate
  int oracle = -1;               // candidate with the lowest ground-truth error; -1: unknown
  std::array<double, 4> oracle_errors{};  // mean error of each candidate (when oracle >= 0)
  StageStatus matching_status;
  StageStatus refine_status;
  // flip, matching, refine, oracle, ground_truth_distances (the last two with ground truth)
  std::vector<StageTime> times;
};

// Mean error of predicted target input ids, one per ground-truth line of `ground_truth`;
// *distance_seconds: the part of the call spent computing the ground truth's distances.
using MeanErrorFunction =
    std::function<double(const std::vector<int>& predicted, double* distance_seconds)>;

// ground_truth: in input ids (PairLines of the shapes' ground truth), or null. mean_error is
// used for the oracle candidate when ground_truth is given and has lines. Throws what a stage
// throws.
PairOutcome ComputePair(const ShapeOutcome& source, const ShapeOutcome& target,
                        const Pipeline& pipeline, const InputGroundTruth* ground_truth,
                        const MeanErrorFunction& mean_error, StageCounters* counters);

// The cache key of a pair's map and evaluation record: both shapes' names and keys (which hold
// the per-shape stages' options), the options of each per-pair kind of kPipelineStageKinds
// (registry/stage_kinds.h) in its order, the evaluation options and the ground truth.
uint64_t PairKey(const ShapeOutcome& source, const ShapeOutcome& target, const Pipeline& pipeline,
                 const InputGroundTruth& ground_truth);

// A map of every source vertex from the ground truth in preprocessed ids (ToPreprocessedIds):
// a vertex with lines takes the target of its first line; one without takes that of the lined
// vertex nearest along the surface's edges (graph distance), or, in a part of the surface with
// no lined vertex, the Euclidean nearest. The refine stage's start under `evaluation.
// refine_start: ground_truth`. Throws InvalidInputError when there are no lines or an id is out
// of range.
std::vector<int> MapFromGroundTruth(const Surface& source, int target_vertices,
                                    const PreprocessedGroundTruth& ground_truth);

// Ground truth in input ids -> preprocessed ids; lines whose source or target vertex was removed
// are dropped (PairInput::ground_truth, used by the oracle flip scorer).
PreprocessedGroundTruth ToPreprocessedIds(const InputGroundTruth& ground_truth,
                                          const ShapeOutcome& source, const ShapeOutcome& target);

}  // namespace symembed

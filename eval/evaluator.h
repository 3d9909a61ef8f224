// Geodesic error of correspondence maps against ground truth.
//
// For every ground-truth line i of a pair A -> B with source point a_i and target point b_i,
// the error of a map T is d_B(T(a_i), b_i) / sqrt(area(B)) [Kim et al. 2011] Blended
// intrinsic maps, measured on B's surface after preprocessing (the preprocess scale cancels
// in the ratio). With a symmetric ground truth b'_i, the same is measured against b'_i; the
// flip-tolerant error of a pair is the one of the two with the lower mean [Ren et al. 2018]
// Continuous and orientation-preserving correspondences via functional maps.
//
// Distances come from the registered geodesics stage named by evaluation.geodesics, computed
// only from the sources a pair needs and cached per target shape (keyed by its name) for the
// life of the Evaluator. Which endpoint is the source is decided per pair from the pair alone,
// so results never depend on the cache or on the order pairs are evaluated in: ground-truth
// points (shared by every pair with this target) unless the map's distinct image is less than
// half their number, then the map's image points.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "eval/evaluation_options.h"
#include "eval/metrics.h"
#include "registry/stages.h"

namespace symembed {

// A target shape as the evaluator measures on it.
struct EvalShape {
  Surface surface;                   // after the dataset pipeline's preprocess stage
  std::vector<int> vertex_of_input;  // #input vertices: vertex of `surface` per input id
  double area = 0.0;                 // TotalArea(surface)
  int NumInputVertices() const { return static_cast<int>(vertex_of_input.size()); }
};

// pre: the preprocess output of the shape; input: the input mesh (before preprocessing).
// An input vertex removed by preprocessing is looked up as the kept vertex nearest to it in
// Euclidean distance (in input coordinates). Throws InvalidInputError for inconsistent input.
EvalShape MakeEvalShape(const PreprocessResult& pre, const Surface& input);
// Same when preprocessing kept every input vertex (throws InvalidInputError otherwise).
EvalShape MakeEvalShape(const PreprocessResult& pre, int num_input_vertices);

// The lines of gt kept by evaluation.points = n (0 or n >= #lines: all lines, unchanged):
// Euclidean farthest-point sampling of the target points b_i on target.surface, starting from
// line 0, ties to the lowest line index; the kept lines stay in their original order.
// (Kim et al. 2011 evaluate 1,024 FPS points; Euclidean FPS is deterministic and cheap.)
InputGroundTruth SelectPoints(const InputGroundTruth& gt, const EvalShape& target, int n);

// Default memory budget of the cached distance rows, MiB: a 5k-vertex target with every
// ground-truth point takes about 100 MB, and rows are computed only from the sources pairs need.
inline constexpr double kDefaultEvaluationCacheMb = 1024.0;

class Evaluator {
 public:
  // geodesics must outlive the Evaluator. cache_budget_mb bounds the cached distance rows
  // (float, #V each); whole targets are evicted least recently used first.
  Evaluator(const EvaluationOptions& options, const GeodesicsStage& geodesics,
            double cache_budget_mb = kDefaultEvaluationCacheMb);
  ~Evaluator();

  // Scores one map A -> B. target: B (name target_name, same shape for every call with that
  // name); map_input_ids: 0-based B input id per A input vertex; gt: from PairLines (input ids,
  // gt.target_sym_ids may be empty); chosen/oracle: candidate indices (-1 unknown). Never
  // throws for bad data: a map or ground truth that does not fit, or a solver failure, gives a
  // record with ok = false and the message. Sets stage_seconds["evaluation"]. Thread-safe.
  PairEvaluation Evaluate(const std::string& source_name, const std::string& target_name,
                          const EvalShape& target, const std::vector<int>& map_input_ids,
                          const InputGroundTruth& gt, int chosen = -1, int oracle = -1) const;

  // Mean direct error of a map over the (selected) ground-truth lines, for choosing the
  // oracle's candidate. distance_seconds (optional): gets the seconds this call spent computing
  // distance rows the target's cache lacked (exactly 0 when it had them all). Throws InvalidInputError
  // when the map does not fit. Thread-safe.
  double MeanError(const std::string& target_name, const EvalShape& target,
                   const std::vector<int>& map_input_ids, const InputGroundTruth& gt,
                   double* distance_seconds = nullptr) const;

  const EvaluationOptions& options() const { return options_; }
  // Distance rows computed so far (single-source solves), for tests and reports.
  int64_t RowsComputed() const;

 private:
  struct TargetCache;
  // Errors of each line against gt.target_ids (and target_sym_ids into *sym when given).
  // distance_seconds (optional): the seconds spent computing missing distance rows.
  std::vector<double> Errors(const std::string& target_name, const EvalShape& target,
                             const std::vector<int>& map_input_ids, const InputGroundTruth& gt,
                             std::vector<double>* sym, double* distance_seconds = nullptr) const;
  std::shared_ptr<TargetCache> Acquire(const std::string& target_name) const;
  void Account(const std::string& target_name, TargetCache& entry, int64_t rows,
               int64_t bytes) const;

  EvaluationOptions options_;
  const GeodesicsStage& geodesics_;
  int64_t budget_bytes_;
  mutable std::mutex mutex_;  // guards cache_, clock_, total_bytes_, rows_computed_
  mutable std::map<std::string, std::shared_ptr<TargetCache>> cache_;
  mutable uint64_t clock_ = 0;
  mutable int64_t total_bytes_ = 0;
  mutable int64_t rows_computed_ = 0;
};

}  // namespace symembed

// The experiment runner (`symembed run`): every variant of a config (or one), per-shape work
// then per-pair work on a thread pool, per-shape stage outputs cached on disk
// (harness/shape_pipeline.h), every finished pair written at once so that a killed run resumes.
// Shapes whose mesh files hold identical bytes are computed once, with or without the cache,
// each keeping its own record, ground truth and failures (harness/content_groups.h).
//
// Outputs under out_dir (results/<experiment>):
//   variants.txt                    the config's variant names in order
//   <variant>/config.yaml           ResolvedConfigYaml
//   <variant>/maps/STEM.map         1-based target input id per source input vertex (atomic)
//   <variant>/IN_PROGRESS           while the variant runs (harness/run_outputs.h)
//   <variant>/pairs/STEM.rec        the pair's record (SerializePairRecord, eval/report.h: the
//                                   evaluation with the pair's PairInputs; atomic, after the map)
//   (STEM: "A_B", escaped where that is ambiguous among all the variant's pairs, shards
//   included: eval/pair_names.h)
//   <variant>/shapes/NAME.rec       per-shape stage times and report (harness/run_outputs.h)
//   <variant>/failures.csv          every failed shape and pair with its message
//   + what RunEvaluation::WriteVariant / WriteExperiment write (summary, curves, comparison).
// A pair that succeeded is cached too (its map and record, under PairKey: both shapes' keys,
// the per-pair stages' and the evaluation's options, the ground truth), so a second identical
// run recomputes nothing at all.
// Pairs are processed in (source, target) order; shard i of N takes the pairs PairShards
// (harness/shards.h) assigns to it: by pair index modulo N, or all pairs of a target together.
// Whatever is in the variant folder depends only on the set of pair records and failures, so
// shards merged (MergeRuns) and resumed runs equal a single run.
// --resume keeps a pair only when its record parses, is the record of that pair, carries this
// run's PairInputs and its map holds one id per source vertex; every other pair is computed
// again, with a warning. Each record is parsed once: a kept pair's from its file, a cached
// pair's from the cache, a computed pair's from the text written (JSON writes non-finite
// numbers as null, read back as NaN: a fresh, a resumed and a merged run see the same values);
// the variant's summary files are written from the parsed records.
//
// A shapes-only run computes the per-shape stages (and what the per-pair stages need of each
// shape) of the shapes of shard i of N (ShapesOfShard over the shapes of all the variant's
// pairs; a shape whose mesh bytes are another's goes with the first of them) for every variant,
// into the cache, and writes nothing else: run with N shards before the pair shards, no shape
// is computed by two processes and the pair shards find every shape cached.
//
// The runner reaches the evaluation through RunEvaluation (harness/run_evaluation.h
// GroundTruthRunEvaluation; the tests give it a fake evaluation).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "eval/metrics.h"
#include "harness/config.h"
#include "harness/pair_pipeline.h"
#include "harness/run_outputs.h"
#include "harness/shape_pipeline.h"
#include "harness/shards.h"

namespace symembed {

// What the evaluation sees of one pair.
struct PairContext {
  const DatasetShape& source_info;
  const DatasetShape& target_info;
  const ShapeOutcome& source;
  const ShapeOutcome& target;
  const InputGroundTruth& ground_truth;  // input ids (PairLines); empty without ground truth
};

// The evaluation of one variant's pairs. Thread-safe.
class VariantEvaluation {
 public:
  virtual ~VariantEvaluation() = default;
  // Mean direct error of predicted target input ids, one per line of pair.ground_truth
  // (chooses the oracle candidate); *distance_seconds: the part of the call spent computing the
  // target's ground-truth distances. May throw; the pair then fails.
  virtual double MeanError(const PairContext& pair, const std::vector<int>& predicted,
                           double* distance_seconds) const = 0;
  // The record of a finished pair, without its inputs (the runner adds them and writes it to
  // pairs/STEM.rec). When the evaluation failed, sets *failure to the message; the pair is then
  // a failure and no record is written.
  virtual PairEvaluation Evaluate(const PairContext& pair, const PairOutcome& outcome,
                                  std::string* failure) const = 0;
};

struct VariantResults {
  std::string variant;
  std::string dir;                   // the variant folder (holds config.yaml)
  std::vector<DatasetPair> pairs;    // the run's pairs, in (source, target) order
  // Per pair: its record, as its file reads back (inputs included); none when it failed.
  std::vector<std::optional<PairEvaluation>> records;
  std::vector<Failure> failures;     // sorted
  std::vector<ShapeRecord> shapes;   // shapes of the pairs that have a record, by name
  double wall_seconds = 0.0;
  std::vector<std::string> merged_from;  // MergeRuns: the shards' variant folders; else empty
};

class RunEvaluation {
 public:
  virtual ~RunEvaluation() = default;
  virtual std::unique_ptr<VariantEvaluation> ForVariant(const Pipeline& pipeline) = 0;
  // Writes the variant's summary files from its records (also used by MergeRuns).
  virtual void WriteVariant(const VariantResults& results) = 0;
  // Writes the cross-variant files of the experiment folder (variants in config order; the
  // ones without outputs in the folder are skipped).
  virtual void WriteExperiment(const std::string& dir,
                               const std::vector<std::string>& variants) = 0;
};

struct RunOptions {
  std::string out_dir;    // results/<experiment>
  std::string cache_dir;  // per-shape cache; empty: none
  std::string variant;    // run only this one (empty: all)
  int jobs = 0;           // worker threads (0: all cores)
  bool resume = false;    // keep the pairs whose record and map match this run's inputs
  int shard_index = 0;    // this run's shard, in [0, shard_count)
  int shard_count = 1;
  ShardSplit shard_split = ShardSplit::kPair;  // how pairs are split into shards
  bool shapes_only = false;  // compute and cache the shard's shapes only (needs cache_dir)
  // Called after each shape of a shapes-only run with the shape, the variant and the stages
  // it computed (not found in the cache), sorted by name; for a shape whose mesh file has the
  // bytes of another shape's, nothing computed and that shape (computed_with, else empty).
  // The runner serialises the calls.
  std::function<void(const std::string& shape, const std::string& variant,
                     const std::vector<std::string>& computed, const std::string& computed_with)>
      on_shape;
  bool quiet = false;
  // Also write each shape's canonical embedding, the surface the matching stage compares (the
  // symmetrized embedding in its canonical frame, on the preprocessed faces), as
  // OUT/<variant>/embeddings/NAME.off: to look at the symmetry plane and the frame of a shape.
  bool write_embeddings = false;
  MeshLoader load_mesh;  // reads a mesh file (core/mesh_io.h LoadSurface)
};

struct RunStats {
  std::map<std::string, int> executed;    // stage -> computations (cache misses included)
  std::map<std::string, int> cache_hits;  // stage -> disk cache hits
  int shapes_computed = 0;         // shapes done (computed or loaded), all variants
  // Of those, shapes whose mesh file has the bytes of another shape's of the variant: computed
  // once with it (harness/content_groups.h).
  int shapes_shared = 0;
  int pairs_total = 0;            // pairs of the run (shard), all variants
  int pairs_skipped = 0;          // kept from an earlier run (--resume)
  int pairs_recomputed = 0;       // --resume: had a record that did not prove itself
  // One per pair computed again, naming its record and why, and one per shape whose second plane
  // hypothesis was dropped, naming its mesh.
  std::vector<std::string> warnings;
  int pairs_done = 0;             // computed now
  std::vector<Failure> failures;  // this run's, all variants
  bool ok() const { return failures.empty(); }
};

// Runs the experiment (or, with options.shapes_only, fills the cache with a shard's shapes).
// Per-shape and per-pair failures are recorded and the run goes on; a config, dataset index or
// output folder problem throws (ConfigError, InvalidInputError, IoError), and so does a
// shapes-only run without a cache folder.
RunStats RunExperiment(const ExperimentConfig& config, const Registry& registry,
                       const RunOptions& options, RunEvaluation& evaluation);

// Writes failures.csv (sorted, without duplicates) and shapes.csv into results.dir and hands
// the variant to evaluation.WriteVariant: the end of a variant for RunExperiment and MergeRuns.
void FinishVariant(VariantResults results, RunEvaluation& evaluation);

}  // namespace symembed

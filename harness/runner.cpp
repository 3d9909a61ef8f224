#include "harness/runner.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>

#include "core/clock.h"
#include "core/files.h"
#include "core/map_io.h"
#include "core/mesh_io.h"
#include "core/parallel.h"
#include "eval/pair_names.h"
#include "eval/report.h"
#include "harness/content_groups.h"
#include "harness/progress.h"
#include "registry/options.h"

namespace fs = std::filesystem;

namespace symembed {
namespace {

// The lines of a YAML text that are not comments.
std::string WithoutComments(const std::string& text) {
  std::string out;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (text.compare(start, 1, "#") != 0) out.append(text, start, end - start).push_back('\n');
    start = end + 1;
  }
  return out;
}

// A pair's cached result (the runner only caches pairs that succeeded): its map and its record
// without inputs (SerializePairRecord).
struct PairEntry {
  std::vector<int> map;
  std::string record;
};

void Write(ArchiveWriter& out, const PairEntry& entry) {
  out.Ints(entry.map);
  out.String(entry.record);
}

void Read(ArchiveReader& in, PairEntry* entry) {
  entry->map = in.Ints();
  entry->record = in.String();
}

std::string VariantsText(const ExperimentConfig& config) {
  std::string text;
  for (const auto& v : config.variants) text += v.name + "\n";
  return text;
}

// The work of one variant.
class VariantRun {
 public:
  // `indexes`: the datasets RunExperiment read, by OptionsText of their stage.
  // `targets_descending`: take the targets' pairs in descending order of the target's name.
  VariantRun(const ExperimentConfig& config, const VariantConfig& variant, const Registry& registry,
             const RunOptions& options, RunEvaluation& evaluation, StageCounters* counters,
             RunStats* stats, const std::map<std::string, DatasetIndex>& indexes,
             bool targets_descending)
      : config_(config),
        variant_(variant),
        options_(options),
        evaluation_(evaluation),
        counters_(counters),
        stats_(stats),
        pipeline_(BuildPipeline(config, variant, registry)),
        dir_(options.out_dir + "/" + variant.name),
        cache_(options.cache_dir),
        index_(indexes.at(OptionsText(*pipeline_.dataset))),
        targets_descending_(targets_descending) {}

  void Run() {
    if (options_.shapes_only) {
      ComputeShapes(ContentGroupsOfShard(ShapesOfPairs(SortedPairs(index_.pairs)), index_,
                                         options_.shard_index, options_.shard_count,
                                         options_.jobs));
      stats_->failures.insert(stats_->failures.end(), failures_.begin(), failures_.end());
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    const std::string resolved = ResolvedConfigYaml(config_, variant_, pipeline_);
    if (options_.resume) {
      // Records made under other settings must not be mixed into this run's outputs.
      // The leading comment names the config file by the path it was given; the same config
      // named by another path (relative, absolute) resumes.
      auto previous = ReadFileBytes(VariantConfigPath(dir_));
      if (previous && WithoutComments(*previous) != WithoutComments(resolved)) {
        throw ConfigError(dir_ +
                          "/config.yaml: the resolved config differs from the one of the "
                          "run being resumed; run without --resume (or into another --out)");
      }
    }
    MarkInProgress(dir_, "symembed run (variant " + variant_.name + ")");
    if (!options_.resume) RemoveEarlierOutputs();
    WriteFileAtomically(VariantConfigPath(dir_), resolved);
    SelectPairs();
    ComputeShapes(GroupByContent(ShapesOfPending(), index_, options_.jobs));
    VerifyKeptPairs();
    ComputePairs();
    shapes_.clear();
    VariantResults results;
    results.variant = variant_.name;
    results.dir = dir_;
    results.pairs = pairs_;
    results.records = records_;
    results.failures = failures_;
    results.wall_seconds = SecondsSince(start);
    FinishVariant(std::move(results), evaluation_);
    ClearInProgress(dir_);
    stats_->failures.insert(stats_->failures.end(), failures_.begin(), failures_.end());
  }

 private:
  void Fail(const std::string& kind, const std::string& source, const std::string& target,
            const std::string& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    failures_.push_back({kind, source, target, message});
  }

  // A run into a folder that holds an earlier run's outputs must not leave them beside its own:
  // not its tables, and not the maps and records of pairs this run does not have (a merge or an
  // eval of the folder would take them for this run's).
  void RemoveEarlierOutputs() {
    std::error_code ec;
    for (const char* file : {"summary.json", "pairs.csv", "curve.csv", "timings.csv",
                             "failures.csv", "shapes.csv"}) {
      fs::remove(dir_ + "/" + file, ec);
    }
    for (const char* folder : {"maps", "pairs", "embeddings"}) {
      fs::remove_all(dir_ + "/" + folder, ec);
      if (ec) {
        throw IoError(dir_ + "/" + folder + ": cannot remove the earlier run's outputs: " +
                      ec.message());
      }
    }
  }

  void SelectPairs() {
    if (index_.pairs.empty()) {
      throw InvalidInputError("variant " + variant_.name + ": the dataset (" +
                              OptionsText(*pipeline_.dataset) + ") has no pairs to run");
    }
    const std::vector<DatasetPair> all = SortedPairs(index_.pairs);
    // From all the variant's pairs, not this shard's: every shard and the merge name alike.
    names_ = PairNames(all);
    const std::vector<int> shard = PairShards(all, options_.shard_split, options_.shard_count);
    for (size_t i = 0; i < all.size(); ++i) {
      if (shard[i] == options_.shard_index) pairs_.push_back(all[i]);
    }
    records_.assign(pairs_.size(), std::nullopt);
    for (size_t i = 0; i < pairs_.size(); ++i) {
      const std::string record = PairRecordPath(dir_, Stem(pairs_[i]));
      if (options_.resume) {
        if (fs::exists(record)) {
          kept_.push_back(static_cast<int>(i));  // verified once its shapes are known
          continue;
        }
      }
      pending_.push_back(static_cast<int>(i));
    }
    stats_->pairs_total += static_cast<int>(pairs_.size());
  }

  std::vector<std::string> ShapesOfPending() const {
    std::set<std::string> names;
    for (const std::vector<int>* list : {&pending_, &kept_}) {
      for (int i : *list) {
        names.insert(pairs_[i].source);
        names.insert(pairs_[i].target);
      }
    }
    return {names.begin(), names.end()};
  }

  void WriteEmbedding(const ShapeOutcome& outcome) const {
    const std::string dir = dir_ + "/embeddings";
    fs::create_directories(dir);
    SaveMesh(dir + "/" + outcome.name + ".off", Surface{outcome.data->Y, outcome.data->surface.F});
  }

  // Computes (or loads) the shapes of `groups`, each group's content once. A full run keeps them
  // for its pairs and writes their records; a shapes-only run only leaves them in the cache and
  // reports each.
  void ComputeShapes(const std::vector<ContentGroup>& groups) {
    int count = 0;
    for (const ContentGroup& group : groups) count += static_cast<int>(group.names.size());
    std::vector<std::vector<NamedOutcome>> outcomes(groups.size());
    Progress progress(variant_.name + ": shapes", count, DefaultProgressMode(options_.quiet),
                      std::cerr);
    ParallelFor(
        static_cast<int>(groups.size()),
        [&](int g) {
          // Counted per group first, so a shapes-only run can say what this content computed.
          StageCounters group_counters;
          const ShapeContext context{&cache_, &group_counters};
          outcomes[g] =
              ComputeContentGroup(groups[g], index_, pipeline_, options_.load_mesh, context);
          bool any_done = false;
          for (size_t k = 0; k < outcomes[g].size(); ++k) {
            NamedOutcome& named = outcomes[g][k];
            const std::string& name = groups[g].names[k];
            if (named.outcome) {
              any_done = true;
              try {
                FinishShape(name, named, group_counters);
              } catch (const std::exception& e) {
                const std::string& path = index_.Find(name)->mesh_path;
                Fail("shape", name, "", FailureNamingFile(e.what(), path, path));
                named.outcome.reset();
              }
              if (options_.shapes_only) named.outcome.reset();  // it is in the cache
            } else {
              Fail("shape", name, "", named.failure);
            }
            progress.Tick();
          }
          if (any_done) counters_->Add(group_counters);
        },
        options_.jobs, 1);
    progress.Finish();
    for (size_t g = 0; g < groups.size(); ++g) {
      for (size_t k = 0; k < groups[g].names.size(); ++k) {
        if (outcomes[g][k].outcome) {
          shapes_[groups[g].names[k]] = std::move(outcomes[g][k].outcome);
        }
      }
    }
  }

  // Writes the record (and embedding) of a shape that has its outcome, or reports it in a
  // shapes-only run, and counts it. counters: what its group's computation ran or loaded.
  void FinishShape(const std::string& name, NamedOutcome& named, const StageCounters& counters) {
    ShapeOutcome& outcome = *named.outcome;
    const std::vector<std::string> warnings = std::move(outcome.warnings);
    if (options_.shapes_only) {
      ReportShape(name, named.reused ? nullptr : &counters, named.computed_with);
    } else {
      ShapeRecord record{outcome.name, outcome.times, outcome.report};
      WriteFileAtomically(ShapeRecordPath(dir_, outcome.name), FormatShapeRecord(record));
      if (options_.write_embeddings) WriteEmbedding(outcome);
    }
    const std::string& mesh_path = index_.Find(name)->mesh_path;
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_->shapes_computed;
    if (named.reused) ++stats_->shapes_shared;
    for (const std::string& warning : warnings) {
      stats_->warnings.push_back(mesh_path + ": " + warning);
    }
  }

  // --resume keeps a pair only when its record reads back, carries the inputs of this run and
  // its map is a complete map between the two meshes; any other pair is computed again.
  void VerifyKeptPairs() {
    for (int i : kept_) {
      const DatasetPair& pair = pairs_[i];
      const std::string path = PairRecordPath(dir_, Stem(pair));
      const std::optional<PairSetup> setup = Setup(pair);
      if (!setup) {
        pending_.push_back(i);  // a shape failed: RunPair records the pair's failure
        continue;
      }
      std::string problem;
      std::optional<PairEvaluation> record;
      try {
        const std::optional<std::string> text = ReadFileBytes(path);
        if (!text) throw InvalidInputError("cannot read it");
        record = ParsePairRecord(*text, path);
        if (record->source != pair.source || record->target != pair.target) {
          problem = "it holds the record of " + record->source + " -> " + record->target;
        } else {
          problem = InputsProblem(record->inputs, setup->inputs);
        }
      } catch (const std::exception& e) {
        problem = std::string("unreadable record (") + e.what() + ")";
      }
      const std::string map_path = PairMapPath(dir_, Stem(pair));
      if (problem.empty() && !fs::exists(map_path)) problem = "its map " + map_path + " is missing";
      if (problem.empty()) {
        try {
          ReadMapFile(map_path, 1, setup->source->input.NumVertices(),
                      setup->target->input.NumVertices());
        } catch (const std::exception& e) {
          problem = std::string("its map ") + e.what();  // the message starts with the path
        }
      }
      if (problem.empty()) {
        records_[i] = std::move(record);
        ++stats_->pairs_skipped;
        continue;
      }
      stats_->warnings.push_back(path + ": computed again: " + problem);
      ++stats_->pairs_recomputed;
      pending_.push_back(i);
    }
    kept_.clear();
    // Pairs of one target run together: the evaluator computes and caches distances per target
    // and evicts whole targets, least recently used first, so this order computes each
    // target's distances about once per variant. The variants of a run share the evaluator and
    // take the targets in alternate directions, so each starts with the targets the one before
    // left in the cache (in one direction every variant would find its next target evicted
    // when the cache holds fewer than all). Outputs do not depend on the order.
    std::sort(pending_.begin(), pending_.end(), [&](int a, int b) {
      const std::string& ta = pairs_[a].target;
      const std::string& tb = pairs_[b].target;
      if (ta != tb) return targets_descending_ ? tb < ta : ta < tb;
      return a < b;
    });
  }

  static std::string InputsProblem(const std::optional<PairInputs>& recorded,
                                   const PairInputs& now) {
    if (!recorded) return "the record carries no inputs (written by an older symembed)";
    if (recorded->source != now.source) return "the source mesh or a per-shape option changed";
    if (recorded->target != now.target) return "the target mesh or a per-shape option changed";
    if (recorded->pair != now.pair) return "a per-pair option or the ground truth changed";
    return "";
  }

  // What a pair is computed from; std::nullopt when one of its shapes failed.
  struct PairSetup {
    const ShapeOutcome* source = nullptr;
    const ShapeOutcome* target = nullptr;
    InputGroundTruth truth;
    PairInputs inputs;
  };

  std::optional<PairSetup> Setup(const DatasetPair& pair) const {
    auto source = shapes_.find(pair.source);
    auto target = shapes_.find(pair.target);
    if (source == shapes_.end() || target == shapes_.end()) return std::nullopt;
    PairSetup setup;
    setup.source = source->second.get();
    setup.target = target->second.get();
    setup.truth = PairGroundTruth(setup.source->ground_truth, setup.source->name,
                                  setup.target->ground_truth, setup.target->name);
    setup.inputs = {setup.source->key, setup.target->key,
                    PairKey(*setup.source, *setup.target, pipeline_, setup.truth)};
    return setup;
  }

  const std::string& Stem(const DatasetPair& pair) const {
    return names_.Stem(pair.source, pair.target);
  }

  // counters: what the shape's computation ran or loaded; null when it was computed with
  // another shape (computed_with).
  void ReportShape(const std::string& name, const StageCounters* counters,
                   const std::string& computed_with) {
    if (!options_.on_shape) return;
    std::vector<std::string> computed;
    if (counters) {
      for (const auto& [stage, n] : counters->executed()) computed.push_back(stage);
    }
    std::lock_guard<std::mutex> lock(mutex_);
    options_.on_shape(name, variant_.name, computed, computed_with);
  }

  void ComputePairs() {
    std::unique_ptr<VariantEvaluation> evaluation = evaluation_.ForVariant(pipeline_);
    Progress progress(variant_.name + ": pairs", static_cast<int>(pending_.size()),
                      DefaultProgressMode(options_.quiet), std::cerr);
    ParallelFor(
        static_cast<int>(pending_.size()),
        [&](int k) {
          const int i = pending_[k];
          const DatasetPair& pair = pairs_[i];
          try {
            records_[i] = RunPair(pair, *evaluation);
          } catch (const std::exception& e) {
            Fail("pair", pair.source, pair.target, e.what());
          }
          progress.Tick();
        },
        options_.jobs, 1);
    progress.Finish();
  }

  // Returns the pair's record (none when the pair failed; the failure is recorded).
  std::optional<PairEvaluation> RunPair(const DatasetPair& pair,
                                        const VariantEvaluation& evaluation) {
    const std::optional<PairSetup> setup = Setup(pair);
    if (!setup) {
      const std::string name = shapes_.count(pair.source) ? pair.target : pair.source;
      Fail("pair", pair.source, pair.target, "shape '" + name + "' failed");
      return std::nullopt;
    }
    const ShapeOutcome& source = *setup->source;
    const ShapeOutcome& target = *setup->target;
    const InputGroundTruth& truth = setup->truth;
    const std::string record_path = PairRecordPath(dir_, Stem(pair));
    PairEntry cached;
    if (cache_.Load("pair", setup->inputs.pair, &cached)) {
      counters_->Hit("pair");
      PairEvaluation record =
          ParsePairRecord(cached.record, cache_.Path("pair", setup->inputs.pair));
      record.inputs = setup->inputs;
      WriteFileAtomically(PairMapPath(dir_, Stem(pair)), FormatMap(cached.map));
      WriteFileAtomically(record_path, SerializePairRecord(record));
      std::lock_guard<std::mutex> lock(mutex_);
      ++stats_->pairs_done;
      return record;
    }
    const PairContext context{*index_.Find(pair.source), *index_.Find(pair.target), source, target,
                              truth};
    const PairOutcome outcome = ComputePair(
        source, target, pipeline_, truth.source_ids.empty() ? nullptr : &truth,
        [&](const std::vector<int>& predicted, double* distance_seconds) {
          return evaluation.MeanError(context, predicted, distance_seconds);
        },
        counters_);
    WriteFileAtomically(PairMapPath(dir_, Stem(pair)), FormatMap(outcome.map));
    std::string failure;
    PairEvaluation evaluated = evaluation.Evaluate(context, outcome, &failure);
    if (!failure.empty()) {
      Fail("pair", pair.source, pair.target, failure);
      return std::nullopt;
    }
    evaluated.inputs.reset();
    const PairEntry entry{outcome.map, SerializePairRecord(evaluated)};
    evaluated.inputs = setup->inputs;
    const std::string text = SerializePairRecord(evaluated);
    WriteFileAtomically(record_path, text);
    counters_->Executed("pair");
    cache_.Store("pair", setup->inputs.pair, entry);
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_->pairs_done;
    // As the file reads back (non-finite numbers are written as null and read back as NaN), as
    // a resumed run and shards merged see it.
    return ParsePairRecord(text, record_path);
  }

  const ExperimentConfig& config_;
  const VariantConfig& variant_;
  const RunOptions& options_;
  RunEvaluation& evaluation_;
  StageCounters* counters_;
  RunStats* stats_;
  Pipeline pipeline_;
  std::string dir_;
  DiskCache cache_;
  const DatasetIndex& index_;
  bool targets_descending_;
  PairNames names_;  // the file stems of all the variant's pairs
  std::vector<DatasetPair> pairs_;
  std::vector<std::optional<PairEvaluation>> records_;
  std::vector<int> pending_;
  std::vector<int> kept_;  // --resume: pairs with a record, until VerifyKeptPairs
  std::map<std::string, std::unique_ptr<ShapeOutcome>> shapes_;
  std::mutex mutex_;  // guards failures_ and stats_ during the parallel phases
  std::vector<Failure> failures_;
};

}  // namespace

namespace {

// Reads the shape records of the shapes used by the pairs that have a record.
std::vector<ShapeRecord> ReadShapeRecords(
    const std::string& dir, const std::vector<DatasetPair>& pairs,
    const std::vector<std::optional<PairEvaluation>>& records) {
  std::set<std::string> names;
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (!records[i]) continue;
    names.insert(pairs[i].source);
    names.insert(pairs[i].target);
  }
  std::vector<ShapeRecord> shapes;
  for (const std::string& name : names) {
    const std::string path = ShapeRecordPath(dir, name);
    if (auto text = ReadFileBytes(path)) shapes.push_back(ParseShapeRecord(name, *text, path));
  }
  return shapes;
}

}  // namespace

// Writes failures.csv and hands the variant to the evaluation.
void FinishVariant(VariantResults results, RunEvaluation& evaluation) {
  std::sort(results.failures.begin(), results.failures.end());
  results.failures.erase(std::unique(results.failures.begin(), results.failures.end()),
                         results.failures.end());
  WriteFileAtomically(results.dir + "/failures.csv", FailuresCsv(results.failures));
  results.shapes = ReadShapeRecords(results.dir, results.pairs, results.records);
  WriteFileAtomically(results.dir + "/shapes.csv", ShapesCsv(results.shapes));
  evaluation.WriteVariant(results);
}

RunStats RunExperiment(const ExperimentConfig& config, const Registry& registry,
                       const RunOptions& options, RunEvaluation& evaluation) {
  if (options.shard_count < 1 || options.shard_index < 0 ||
      options.shard_index >= options.shard_count) {
    throw ConfigError("shard " + std::to_string(options.shard_index) + "/" +
                      std::to_string(options.shard_count) + " is not in [0, N)");
  }
  if (!options.load_mesh) throw ConfigError("the runner needs a mesh loader");
  if (options.shapes_only && options.cache_dir.empty()) {
    throw ConfigError("a shapes-only run needs a cache folder: the cache is all it writes");
  }
  std::vector<const VariantConfig*> variants;
  if (options.variant.empty()) {
    for (const auto& v : config.variants) variants.push_back(&v);
  } else {
    variants.push_back(&config.Get(options.variant));
  }
  if (!options.cache_dir.empty()) {
    std::error_code ec;
    if (fs::exists(options.cache_dir) && !fs::is_directory(options.cache_dir)) {
      throw ConfigError(options.cache_dir + ": the cache must be a folder, and this is a file");
    }
    fs::create_directories(options.cache_dir, ec);
    if (ec) throw IoError(options.cache_dir + ": cannot create the cache folder: " + ec.message());
  }
  // A cache that cannot be written stays empty: fatal when filling it is the run's only
  // purpose, else said once (every run then computes each shape anew).
  std::string unwritable_cache;
  if (!options.cache_dir.empty() && !FolderIsWritable(options.cache_dir)) {
    unwritable_cache = options.cache_dir + ": the cache folder is not writable";
    if (options.shapes_only) {
      throw IoError(unwritable_cache + "; a --shapes-only run writes only the cache");
    }
    unwritable_cache += ": per-shape stages are computed but not cached";
  }
  // Every variant's dataset is read before anything is computed, so that a missing root or a
  // broken index of a later variant does not end the run after the earlier variants ran; each
  // distinct dataset once, for every variant that names it.
  std::map<std::string, DatasetIndex> indexes;
  for (const VariantConfig* v : variants) {
    const Pipeline pipeline = BuildPipeline(config, *v, registry);
    const std::string key = OptionsText(*pipeline.dataset);
    if (indexes.count(key)) continue;
    try {
      indexes[key] = pipeline.dataset->Load();
    } catch (const Error& e) {
      // Where the root was given (a variant's override has its own line), else the section.
      const YAML::Node dataset = v->tree["dataset"];
      const YAML::Node node = dataset.IsMap() && dataset["root"] ? dataset["root"] : dataset;
      throw InvalidInputError(NodeLocation(config.file, node) + ": dataset of variant '" +
                              v->name + "': " + e.what());
    }
  }
  if (!options.shapes_only) {
    fs::create_directories(options.out_dir);
    WriteFileAtomically(VariantsListPath(options.out_dir), VariantsText(config));
  }
  RunStats stats;
  if (!unwritable_cache.empty()) stats.warnings.push_back(unwritable_cache);
  StageCounters counters;
  for (size_t i = 0; i < variants.size(); ++i) {
    VariantRun(config, *variants[i], registry, options, evaluation, &counters, &stats, indexes,
               i % 2 == 1)
        .Run();
  }
  if (!options.shapes_only) {
    std::vector<std::string> names;
    for (const auto& v : config.variants) names.push_back(v.name);
    evaluation.WriteExperiment(options.out_dir, names);
  }
  stats.executed = counters.executed();
  stats.cache_hits = counters.hits();
  return stats;
}

}  // namespace symembed

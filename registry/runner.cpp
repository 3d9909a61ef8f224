#include "registry/runner.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <set>

#include "core/parallel.h"
#include "registry/files.h"
#include "registry/progress.h"

namespace fs = std::filesystem;

namespace symembed {
namespace {

double Since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A pair's cached result (the runner only caches pairs that succeeded).
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

std::string MapText(const std::vector<int>& map) {
  std::string text;
  text.reserve(map.size() * 6);
  for (int t : map) text += std::to_string(t + 1) + "\n";
  return text;
}

std::string VariantsText(const ExperimentConfig& config) {
  std::string text;
  for (const auto& v : config.variants) text += v.name + "\n";
  return text;
}

// The work of one variant.
class VariantRun {
 public:
  VariantRun(const ExperimentConfig& config, const VariantConfig& variant, const Registry& registry,
             const RunOptions& options, RunEvaluation& evaluation, StageCounters* counters,
             RunStats* stats)
      : config_(config),
        variant_(variant),
        options_(options),
        evaluation_(evaluation),
        counters_(counters),
        stats_(stats),
        pipeline_(BuildPipeline(config, variant, registry)),
        dir_(options.out_dir + "/" + variant.name),
        cache_(options.cache_dir) {}

  void Run() {
    if (options_.shapes_only) {
      index_ = pipeline_.dataset->Load();
      ComputeShapes(ShapesOfShard(ShapesOfPairs(SortedPairs(index_.pairs)), options_.shard_index,
                                  options_.shard_count));
      stats_->failures.insert(stats_->failures.end(), failures_.begin(), failures_.end());
      return;
    }
    const auto start = std::chrono::steady_clock::now();
    const std::string resolved = ResolvedConfigYaml(config_, variant_, pipeline_);
    if (options_.resume) {
      // Records made under other settings must not be mixed into this run's outputs.
      auto previous = ReadFileBytes(VariantConfigPath(dir_));
      if (previous && *previous != resolved) {
        throw ConfigError(dir_ +
                          "/config.yaml: the resolved config differs from the one of the "
                          "run being resumed; run without --resume (or into another --out)");
      }
    }
    WriteFileAtomically(VariantConfigPath(dir_), resolved);
    index_ = pipeline_.dataset->Load();
    SelectPairs();
    ComputeShapes(ShapesOfPending());
    ComputePairs();
    shapes_.clear();
    VariantResults results;
    results.variant = variant_.name;
    results.dir = dir_;
    results.pairs = pairs_;
    results.records = records_;
    results.failures = failures_;
    results.wall_seconds = Since(start);
    FinishVariant(std::move(results), evaluation_);
    stats_->failures.insert(stats_->failures.end(), failures_.begin(), failures_.end());
  }

 private:
  void Fail(const std::string& kind, const std::string& source, const std::string& target,
            const std::string& message) {
    std::lock_guard<std::mutex> lock(mutex_);
    failures_.push_back({kind, source, target, message});
  }

  void SelectPairs() {
    const std::vector<DatasetPair> all = SortedPairs(index_.pairs);
    const std::vector<int> shard = PairShards(all, options_.shard_split, options_.shard_count);
    for (size_t i = 0; i < all.size(); ++i) {
      if (shard[i] == options_.shard_index) pairs_.push_back(all[i]);
    }
    records_.assign(pairs_.size(), "");
    for (size_t i = 0; i < pairs_.size(); ++i) {
      const std::string record = PairRecordPath(dir_, pairs_[i].source, pairs_[i].target);
      if (options_.resume) {
        if (auto text = ReadFileBytes(record); text && !text->empty()) {
          records_[i] = *text;
          ++stats_->pairs_skipped;
          continue;
        }
      } else {
        std::error_code ec;
        fs::remove(record, ec);
        fs::remove(PairMapPath(dir_, pairs_[i].source, pairs_[i].target), ec);
      }
      pending_.push_back(static_cast<int>(i));
    }
    // Pairs of one target run together: the evaluator computes and caches distances per target
    // and evicts whole targets, so this order computes each target's distances about once.
    // Outputs do not depend on the order.
    std::stable_sort(pending_.begin(), pending_.end(),
                     [&](int a, int b) { return pairs_[a].target < pairs_[b].target; });
    stats_->pairs_total += static_cast<int>(pairs_.size());
  }

  std::vector<std::string> ShapesOfPending() const {
    std::set<std::string> names;
    for (int i : pending_) {
      names.insert(pairs_[i].source);
      names.insert(pairs_[i].target);
    }
    return {names.begin(), names.end()};
  }

  // Computes (or loads) the shapes `order`. A full run keeps them for its pairs and writes
  // their records; a shapes-only run only leaves them in the cache and reports each.
  void ComputeShapes(const std::vector<std::string>& order) {
    std::vector<std::unique_ptr<ShapeOutcome>> outcomes(order.size());
    Progress progress(variant_.name + ": shapes", static_cast<int>(order.size()),
                      DefaultProgressMode(options_.quiet), std::cerr);
    ParallelFor(
        static_cast<int>(order.size()),
        [&](int i) {
          const DatasetShape* shape = index_.Find(order[i]);
          try {
            if (!shape) throw InvalidInputError("no shape '" + order[i] + "' in the dataset");
            // Counted per shape first, so a shapes-only run can say what this shape computed.
            StageCounters shape_counters;
            ShapeContext context{&cache_, &shape_counters, options_.load_mesh};
            auto outcome = std::make_unique<ShapeOutcome>(ComputeShape(*shape, pipeline_, context));
            counters_->Add(shape_counters);
            if (options_.shapes_only) {
              ReportShape(order[i], shape_counters);
            } else {
              ShapeRecord record{outcome->name, outcome->times, outcome->report};
              WriteFileAtomically(ShapeRecordPath(dir_, outcome->name), FormatShapeRecord(record));
              outcomes[i] = std::move(outcome);
            }
            std::lock_guard<std::mutex> lock(mutex_);
            ++stats_->shapes_computed;
          } catch (const std::exception& e) {
            Fail("shape", order[i], "", e.what());
          }
          progress.Tick();
        },
        options_.jobs, 1);
    progress.Finish();
    for (size_t i = 0; i < order.size(); ++i) {
      if (outcomes[i]) shapes_[order[i]] = std::move(outcomes[i]);
    }
  }

  void ReportShape(const std::string& name, const StageCounters& counters) {
    if (!options_.on_shape) return;
    std::vector<std::string> computed;
    for (const auto& [stage, n] : counters.executed()) computed.push_back(stage);
    std::lock_guard<std::mutex> lock(mutex_);
    options_.on_shape(name, variant_.name, computed);
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

  // Returns the record text (empty when the pair failed; the failure is recorded).
  std::string RunPair(const DatasetPair& pair, const VariantEvaluation& evaluation) {
    auto source = shapes_.find(pair.source);
    auto target = shapes_.find(pair.target);
    for (const auto& [name, it] :
         {std::make_pair(pair.source, source), std::make_pair(pair.target, target)}) {
      if (it == shapes_.end()) {
        Fail("pair", pair.source, pair.target, "shape '" + name + "' failed");
        return "";
      }
    }
    const InputGroundTruth truth =
        PairLines(source->second->ground_truth, target->second->ground_truth);
    const uint64_t key = PairKey(*source->second, *target->second, pipeline_, truth);
    PairEntry cached;
    if (cache_.Load("pair", key, &cached)) {
      counters_->Hit("pair");
      WriteFileAtomically(PairMapPath(dir_, pair.source, pair.target), MapText(cached.map));
      WriteFileAtomically(PairRecordPath(dir_, pair.source, pair.target), cached.record);
      std::lock_guard<std::mutex> lock(mutex_);
      ++stats_->pairs_done;
      return cached.record;
    }
    const PairContext context{*index_.Find(pair.source), *index_.Find(pair.target), *source->second,
                              *target->second, truth};
    const PairOutcome outcome = ComputePair(
        *source->second, *target->second, pipeline_, truth.source_ids.empty() ? nullptr : &truth,
        [&](const std::vector<int>& predicted) { return evaluation.MeanError(context, predicted); },
        counters_);
    WriteFileAtomically(PairMapPath(dir_, pair.source, pair.target), MapText(outcome.map));
    std::string failure;
    std::string record = evaluation.Evaluate(context, outcome, &failure);
    if (!failure.empty()) {
      Fail("pair", pair.source, pair.target, failure);
      return "";
    }
    SYMEMBED_CHECK(!record.empty(), "the evaluation returned an empty record");
    WriteFileAtomically(PairRecordPath(dir_, pair.source, pair.target), record);
    counters_->Executed("pair");
    cache_.Store("pair", key, PairEntry{outcome.map, record});
    std::lock_guard<std::mutex> lock(mutex_);
    ++stats_->pairs_done;
    return record;
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
  DatasetIndex index_;
  std::vector<DatasetPair> pairs_;
  std::vector<std::string> records_;
  std::vector<int> pending_;
  std::map<std::string, std::unique_ptr<ShapeOutcome>> shapes_;
  std::mutex mutex_;  // guards failures_ and stats_ during the parallel phases
  std::vector<Failure> failures_;
};

}  // namespace

namespace {

// Reads the shape records of the shapes used by the pairs that have a record.
std::vector<ShapeRecord> ReadShapeRecords(const std::string& dir,
                                          const std::vector<DatasetPair>& pairs,
                                          const std::vector<std::string>& records) {
  std::set<std::string> names;
  for (size_t i = 0; i < pairs.size(); ++i) {
    if (records[i].empty()) continue;
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
  for (const auto& v : config.variants) {
    if (options.variant.empty() || v.name == options.variant) variants.push_back(&v);
  }
  if (variants.empty()) {
    std::string names;
    for (const auto& v : config.variants) names += (names.empty() ? "" : ", ") + v.name;
    throw ConfigError(config.file + ": no variant '" + options.variant + "'; variants: " + names);
  }
  if (!options.shapes_only) {
    fs::create_directories(options.out_dir);
    WriteFileAtomically(VariantsListPath(options.out_dir), VariantsText(config));
  }
  RunStats stats;
  StageCounters counters;
  for (const VariantConfig* v : variants) {
    VariantRun(config, *v, registry, options, evaluation, &counters, &stats).Run();
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

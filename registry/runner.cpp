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

std::string RecordPath(const std::string& dir, const DatasetPair& p) {
  return dir + "/pairs/" + PairStem(p.source, p.target) + ".rec";
}

std::string MapPath(const std::string& dir, const DatasetPair& p) {
  return dir + "/maps/" + PairStem(p.source, p.target) + ".map";
}

std::string ShapeRecordPath(const std::string& dir, const std::string& shape) {
  return dir + "/shapes/" + shape + ".rec";
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

bool PairLess(const DatasetPair& a, const DatasetPair& b) {
  return std::tie(a.source, a.target) < std::tie(b.source, b.target);
}

bool PairEqual(const DatasetPair& a, const DatasetPair& b) {
  return a.source == b.source && a.target == b.target;
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
    const auto start = std::chrono::steady_clock::now();
    const std::string resolved = ResolvedConfigYaml(config_, variant_, pipeline_);
    if (options_.resume) {
      // Records made under other settings must not be mixed into this run's outputs.
      auto previous = ReadFileBytes(dir_ + "/config.yaml");
      if (previous && *previous != resolved) {
        throw ConfigError(dir_ +
                          "/config.yaml: the resolved config differs from the one of the "
                          "run being resumed; run without --resume (or into another --out)");
      }
    }
    WriteFileAtomically(dir_ + "/config.yaml", resolved);
    index_ = pipeline_.dataset->Load();
    SelectPairs();
    ComputeShapes();
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
    std::vector<DatasetPair> all = index_.pairs;
    std::sort(all.begin(), all.end(), PairLess);
    all.erase(std::unique(all.begin(), all.end(), PairEqual), all.end());
    for (size_t i = 0; i < all.size(); ++i) {
      if (static_cast<int>(i % options_.shard_count) == options_.shard_index) {
        pairs_.push_back(all[i]);
      }
    }
    records_.assign(pairs_.size(), "");
    for (size_t i = 0; i < pairs_.size(); ++i) {
      const std::string record = RecordPath(dir_, pairs_[i]);
      if (options_.resume) {
        if (auto text = ReadFileBytes(record); text && !text->empty()) {
          records_[i] = *text;
          ++stats_->pairs_skipped;
          continue;
        }
      } else {
        std::error_code ec;
        fs::remove(record, ec);
        fs::remove(MapPath(dir_, pairs_[i]), ec);
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

  void ComputeShapes() {
    std::set<std::string> names;
    for (int i : pending_) {
      names.insert(pairs_[i].source);
      names.insert(pairs_[i].target);
    }
    std::vector<std::string> order(names.begin(), names.end());
    std::vector<std::unique_ptr<ShapeOutcome>> outcomes(order.size());
    ShapeContext context{&cache_, counters_, options_.load_mesh};
    Progress progress(variant_.name + ": shapes", static_cast<int>(order.size()),
                      DefaultProgressMode(options_.quiet), std::cerr);
    ParallelFor(
        static_cast<int>(order.size()),
        [&](int i) {
          const DatasetShape* shape = index_.Find(order[i]);
          try {
            if (!shape) throw InvalidInputError("no shape '" + order[i] + "' in the dataset");
            auto outcome = std::make_unique<ShapeOutcome>(ComputeShape(*shape, pipeline_, context));
            ShapeRecord record{outcome->name, outcome->times, outcome->report};
            WriteFileAtomically(ShapeRecordPath(dir_, outcome->name), FormatShapeRecord(record));
            outcomes[i] = std::move(outcome);
          } catch (const std::exception& e) {
            Fail("shape", order[i], "", e.what());
          }
          progress.Tick();
        },
        options_.jobs, 1);
    progress.Finish();
    for (size_t i = 0; i < order.size(); ++i) {
      if (outcomes[i]) {
        shapes_[order[i]] = std::move(outcomes[i]);
        ++stats_->shapes_computed;
      }
    }
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
    const PairGroundTruth truth =
        PairLines(source->second->ground_truth, target->second->ground_truth);
    const uint64_t key = PairKey(*source->second, *target->second, pipeline_, truth);
    PairEntry cached;
    if (cache_.Load("pair", key, &cached)) {
      counters_->Hit("pair");
      WriteFileAtomically(MapPath(dir_, pair), MapText(cached.map));
      WriteFileAtomically(RecordPath(dir_, pair), cached.record);
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
    WriteFileAtomically(MapPath(dir_, pair), MapText(outcome.map));
    std::string failure;
    std::string record = evaluation.Evaluate(context, outcome, &failure);
    if (!failure.empty()) {
      Fail("pair", pair.source, pair.target, failure);
      return "";
    }
    SYMEMBED_CHECK(!record.empty(), "the evaluation returned an empty record");
    WriteFileAtomically(RecordPath(dir_, pair), record);
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

RunStats RunExperiment(const ExperimentConfig& config, const Registry& registry,
                       const RunOptions& options, RunEvaluation& evaluation) {
  if (options.shard_count < 1 || options.shard_index < 0 ||
      options.shard_index >= options.shard_count) {
    throw ConfigError("shard " + std::to_string(options.shard_index) + "/" +
                      std::to_string(options.shard_count) + " is not in [0, N)");
  }
  if (!options.load_mesh) throw ConfigError("the runner needs a mesh loader");
  std::vector<const VariantConfig*> variants;
  for (const auto& v : config.variants) {
    if (options.variant.empty() || v.name == options.variant) variants.push_back(&v);
  }
  if (variants.empty()) {
    std::string names;
    for (const auto& v : config.variants) names += (names.empty() ? "" : ", ") + v.name;
    throw ConfigError(config.file + ": no variant '" + options.variant + "'; variants: " + names);
  }
  fs::create_directories(options.out_dir);
  WriteFileAtomically(options.out_dir + "/variants.txt", VariantsText(config));
  RunStats stats;
  StageCounters counters;
  for (const VariantConfig* v : variants) {
    VariantRun(config, *v, registry, options, evaluation, &counters, &stats).Run();
  }
  std::vector<std::string> names;
  for (const auto& v : config.variants) names.push_back(v.name);
  evaluation.WriteExperiment(options.out_dir, names);
  stats.executed = counters.executed();
  stats.cache_hits = counters.hits();
  return stats;
}

namespace {

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

// Files of a folder with the given extension, sorted by name (none when it does not exist).
std::vector<fs::path> FilesWithExtension(const std::string& dir, const std::string& extension) {
  std::vector<fs::path> files;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (it->is_regular_file() && it->path().extension() == extension) files.push_back(it->path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

void CopyIfPresent(const fs::path& from, const std::string& to) {
  if (auto bytes = ReadFileBytes(from.string())) WriteFileAtomically(to, *bytes);
}

}  // namespace

std::vector<Failure> MergeRuns(const std::vector<std::string>& shard_dirs,
                               const std::string& out_dir, RunEvaluation& evaluation) {
  if (shard_dirs.empty()) throw InvalidInputError("merge: no shard folders given");
  const std::string variants_text = ReadFileOrThrow(shard_dirs[0] + "/variants.txt");
  for (const std::string& shard : shard_dirs) {
    if (ReadFileOrThrow(shard + "/variants.txt") != variants_text) {
      throw InvalidInputError(shard + "/variants.txt: differs from " + shard_dirs[0] +
                              "/variants.txt (shards of different experiments?)");
    }
  }
  fs::create_directories(out_dir);
  WriteFileAtomically(out_dir + "/variants.txt", variants_text);
  const std::vector<std::string> names = Lines(variants_text);
  std::vector<Failure> all_failures;
  for (const std::string& name : names) {
    VariantResults results;
    results.variant = name;
    results.dir = out_dir + "/" + name;
    std::string config_text;
    std::map<std::pair<std::string, std::string>, std::string> records;
    std::set<Failure> failures;
    for (const std::string& shard : shard_dirs) {
      const std::string dir = shard + "/" + name;
      auto config = ReadFileBytes(dir + "/config.yaml");
      if (!config) continue;
      if (results.merged_from.empty()) {
        config_text = *config;
      } else if (*config != config_text) {
        throw InvalidInputError(dir + "/config.yaml: differs from " + results.merged_from[0] +
                                "/config.yaml");
      }
      results.merged_from.push_back(dir);
      for (const fs::path& file : FilesWithExtension(dir + "/pairs", ".rec")) {
        const std::string text = ReadFileOrThrow(file.string());
        const DatasetPair pair = evaluation.PairOfRecord(text, file.string());
        const std::string stem = PairStem(pair.source, pair.target);
        if (file.stem().string() != stem) {
          throw InvalidInputError(file.string() + ": holds the record of " + stem);
        }
        records[{pair.source, pair.target}] = text;
        WriteFileAtomically(results.dir + "/pairs/" + stem + ".rec", text);
        CopyIfPresent(dir + "/maps/" + stem + ".map", results.dir + "/maps/" + stem + ".map");
      }
      for (const fs::path& file : FilesWithExtension(dir + "/shapes", ".rec")) {
        CopyIfPresent(file, results.dir + "/shapes/" + file.filename().string());
      }
      if (auto text = ReadFileBytes(dir + "/failures.csv")) {
        for (Failure& f : ParseFailuresCsv(*text, dir + "/failures.csv")) {
          failures.insert(std::move(f));
        }
      }
    }
    if (results.merged_from.empty()) continue;
    WriteFileAtomically(results.dir + "/config.yaml", config_text);
    // Failed pairs keep their map (written before the evaluation failed), when there is one.
    std::set<std::pair<std::string, std::string>> pair_set;
    for (const auto& [key, text] : records) pair_set.insert(key);
    for (const Failure& f : failures) {
      if (f.kind != "pair" || records.count({f.source, f.target})) continue;
      pair_set.insert({f.source, f.target});
      results.failures.push_back(f);
      const std::string stem = PairStem(f.source, f.target);
      for (const std::string& shard_variant : results.merged_from) {
        CopyIfPresent(shard_variant + "/maps/" + stem + ".map",
                      results.dir + "/maps/" + stem + ".map");
      }
    }
    for (const Failure& f : failures) {
      if (f.kind == "shape") results.failures.push_back(f);
    }
    for (const auto& [source, target] : pair_set) {
      results.pairs.push_back({source, target});
      auto it = records.find({source, target});
      results.records.push_back(it == records.end() ? "" : it->second);
    }
    all_failures.insert(all_failures.end(), results.failures.begin(), results.failures.end());
    FinishVariant(std::move(results), evaluation);
  }
  evaluation.WriteExperiment(out_dir, names);
  return all_failures;
}

}  // namespace symembed

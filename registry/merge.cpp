#include "registry/merge.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "core/errors.h"
#include "registry/files.h"

namespace fs = std::filesystem;

namespace symembed {

namespace {

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
  const std::string variants_text = ReadFileOrThrow(VariantsListPath(shard_dirs[0]));
  for (const std::string& shard : shard_dirs) {
    if (ReadFileOrThrow(VariantsListPath(shard)) != variants_text) {
      throw InvalidInputError(shard + "/variants.txt: differs from " + shard_dirs[0] +
                              "/variants.txt (shards of different experiments?)");
    }
  }
  fs::create_directories(out_dir);
  WriteFileAtomically(VariantsListPath(out_dir), variants_text);
  const std::vector<std::string> names = ParseVariantsList(variants_text);
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
      auto config = ReadFileBytes(VariantConfigPath(dir));
      if (!config) continue;
      RequireNotInProgress(dir);
      if (results.merged_from.empty()) {
        MarkInProgress(results.dir, "symembed merge");
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
        WriteFileAtomically(PairRecordPath(results.dir, pair.source, pair.target), text);
        CopyIfPresent(PairMapPath(dir, pair.source, pair.target),
                      PairMapPath(results.dir, pair.source, pair.target));
      }
      for (const fs::path& file : FilesWithExtension(dir + "/shapes", ".rec")) {
        CopyIfPresent(file, ShapeRecordPath(results.dir, file.stem().string()));
      }
      // Shards run with --write-embeddings (the files are the same in every shard that wrote one).
      for (const fs::path& file : FilesWithExtension(dir + "/embeddings", ".off")) {
        fs::create_directories(results.dir + "/embeddings");
        CopyIfPresent(file, results.dir + "/embeddings/" + file.filename().string());
      }
      if (auto text = ReadFileBytes(dir + "/failures.csv")) {
        for (Failure& f : ParseFailuresCsv(*text, dir + "/failures.csv")) {
          failures.insert(std::move(f));
        }
      }
    }
    if (results.merged_from.empty()) continue;
    WriteFileAtomically(VariantConfigPath(results.dir), config_text);
    // Failed pairs keep their map (written before the evaluation failed), when there is one.
    std::set<std::pair<std::string, std::string>> pair_set;
    for (const auto& [key, text] : records) pair_set.insert(key);
    for (const Failure& f : failures) {
      if (f.kind != "pair" || records.count({f.source, f.target})) continue;
      pair_set.insert({f.source, f.target});
      results.failures.push_back(f);
      for (const std::string& shard_variant : results.merged_from) {
        CopyIfPresent(PairMapPath(shard_variant, f.source, f.target),
                      PairMapPath(results.dir, f.source, f.target));
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
    const std::string variant_dir = results.dir;
    FinishVariant(std::move(results), evaluation);
    ClearInProgress(variant_dir);
  }
  evaluation.WriteExperiment(out_dir, names);
  return all_failures;
}

}  // namespace symembed

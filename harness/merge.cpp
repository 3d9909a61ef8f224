#include "harness/merge.h"

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <set>

#include "core/errors.h"
#include "core/files.h"
#include "core/map_io.h"
#include "eval/pair_names.h"
#include "eval/report.h"

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

// Column `name` of a CSV table's header; throws InvalidInputError naming `where` when absent.
size_t Column(const std::vector<std::string>& header, const std::string& name,
              const std::string& where) {
  const auto it = std::find(header.begin(), header.end(), name);
  if (it == header.end()) throw InvalidInputError(where + ": no column '" + name + "'");
  return static_cast<size_t>(it - header.begin());
}

// The pairs a finished run's variant folder says it computed (its pairs.csv), each with whether
// it succeeded; the records and maps of the folder are proved against this list, as --resume
// proves them, so that a record or map lost or cut short after the run is found, not merged.
// A folder whose evaluation wrote no pairs.csv lists the pairs of its records.
std::vector<std::pair<DatasetPair, bool>> ListedPairs(const std::string& dir) {
  const std::string path = dir + "/pairs.csv";
  const std::optional<std::string> text = ReadFileBytes(path);
  if (!text) {
    std::vector<std::pair<DatasetPair, bool>> pairs;
    for (const fs::path& file : FilesWithExtension(dir + "/pairs", ".rec")) {
      const PairEvaluation record = ParsePairRecord(ReadFileOrThrow(file.string()), file.string());
      pairs.push_back({{record.source, record.target}, true});
    }
    return pairs;
  }
  const auto rows = ParseCsv(*text, path);
  if (rows.empty()) throw InvalidInputError(path + ": empty");
  const size_t source = Column(rows[0], "source", path), target = Column(rows[0], "target", path),
               status = Column(rows[0], "status", path);
  std::vector<std::pair<DatasetPair, bool>> pairs;
  for (size_t r = 1; r < rows.size(); ++r) {
    if (rows[r].size() != rows[0].size()) {
      throw InvalidInputError(path + ": row " + std::to_string(r + 1) + " has " +
                              std::to_string(rows[r].size()) + " fields, the header " +
                              std::to_string(rows[0].size()));
    }
    pairs.push_back({{rows[r][source], rows[r][target]}, rows[r][status] == "ok"});
  }
  return pairs;
}

// Input vertex counts of the shapes of a finished run's variant folder (its shapes.csv), empty
// when its preprocess stage reports none (the standard one does).
std::map<std::string, int> InputVertices(const std::string& dir) {
  const std::string path = dir + "/shapes.csv";
  const std::optional<std::string> text = ReadFileBytes(path);
  std::map<std::string, int> counts;
  if (!text) return counts;
  const auto rows = ParseCsv(*text, path);
  if (rows.empty()) return counts;
  const auto shape_column = std::find(rows[0].begin(), rows[0].end(), "shape");
  const auto vertices_column = std::find(rows[0].begin(), rows[0].end(), "input_vertices");
  if (shape_column == rows[0].end() || vertices_column == rows[0].end()) return counts;
  const size_t shape = static_cast<size_t>(shape_column - rows[0].begin());
  const size_t vertices = static_cast<size_t>(vertices_column - rows[0].begin());
  for (size_t r = 1; r < rows.size(); ++r) {
    if (rows[r].size() <= std::max(shape, vertices)) continue;
    try {
      counts[rows[r][shape]] = std::stoi(rows[r][vertices]);
    } catch (const std::exception&) {
      throw InvalidInputError(path + ": row " + std::to_string(r + 1) +
                              ": input_vertices is not a number");
    }
  }
  return counts;
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
    std::vector<std::vector<std::pair<DatasetPair, bool>>> listed;  // per shard in merged_from
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
      listed.push_back(ListedPairs(dir));
      if (auto text = ReadFileBytes(dir + "/failures.csv")) {
        for (Failure& f : ParseFailuresCsv(*text, dir + "/failures.csv")) {
          failures.insert(std::move(f));
        }
      }
    }
    if (results.merged_from.empty()) continue;
    // The shards' pairs together are the variant's pairs, which the shards' files are named
    // from.
    std::vector<DatasetPair> all_pairs;
    for (const auto& shard_pairs : listed) {
      for (const auto& [pair, ok] : shard_pairs) all_pairs.push_back(pair);
    }
    for (const Failure& f : failures) {
      if (f.kind == "pair") all_pairs.push_back({f.source, f.target});
    }
    const PairNames pair_names(all_pairs);
    const auto stem = [&](const DatasetPair& pair) -> const std::string& {
      return pair_names.Stem(pair.source, pair.target);
    };
    std::map<std::pair<std::string, std::string>, PairEvaluation> records;
    for (size_t s = 0; s < results.merged_from.size(); ++s) {
      const std::string& dir = results.merged_from[s];
      const std::map<std::string, int> vertices = InputVertices(dir);
      const std::string rerun =
          "; rerun this run (or shard) with --resume, which computes it again";
      for (const auto& [listed_pair, ok] : listed[s]) {
        if (!ok) continue;  // a failed pair comes with its failures.csv line
        const std::string file = PairRecordPath(dir, stem(listed_pair));
        const std::optional<std::string> text = ReadFileBytes(file);
        if (!text) {
          throw InvalidInputError(dir + "/pairs.csv lists " + listed_pair.source + " -> " +
                                  listed_pair.target + " as ok, but its record " + file +
                                  " is missing" + rerun);
        }
        PairEvaluation record = ParsePairRecord(*text, file);
        const DatasetPair pair{record.source, record.target};
        if (pair.source != listed_pair.source || pair.target != listed_pair.target) {
          throw InvalidInputError(file + ": holds the record of " + pair.source + " -> " +
                                  pair.target);
        }
        // The map, read once: its length and ids against the shapes' vertex counts where
        // shapes.csv gives them, then its bytes copied.
        const std::string map = PairMapPath(dir, stem(pair));
        const std::optional<std::string> map_text = ReadFileBytes(map);
        const auto source_vertices = vertices.find(pair.source);
        const auto target_vertices = vertices.find(pair.target);
        try {
          if (!map_text) throw IoError(map + ": cannot read");
          ParseMap(*map_text, 1, source_vertices == vertices.end() ? -1 : source_vertices->second,
                   target_vertices == vertices.end() ? -1 : target_vertices->second, map);
        } catch (const Error& e) {
          throw InvalidInputError(std::string("the map of ") + file + ": " + e.what() + rerun);
        }
        records[{pair.source, pair.target}] = std::move(record);
        WriteFileAtomically(PairRecordPath(results.dir, stem(pair)), *text);
        WriteFileAtomically(PairMapPath(results.dir, stem(pair)), *map_text);
      }
      for (const fs::path& file : FilesWithExtension(dir + "/shapes", ".rec")) {
        CopyIfPresent(file, ShapeRecordPath(results.dir, file.stem().string()));
      }
      // Shards run with --write-embeddings (the files are the same in every shard that wrote one).
      for (const fs::path& file : FilesWithExtension(dir + "/embeddings", ".off")) {
        fs::create_directories(results.dir + "/embeddings");
        CopyIfPresent(file, results.dir + "/embeddings/" + file.filename().string());
      }
    }
    WriteFileAtomically(VariantConfigPath(results.dir), config_text);
    // Failed pairs keep their map (written before the evaluation failed), when there is one.
    std::set<std::pair<std::string, std::string>> pair_set;
    for (const auto& [key, record] : records) pair_set.insert(key);
    for (const Failure& f : failures) {
      if (f.kind != "pair" || records.count({f.source, f.target})) continue;
      pair_set.insert({f.source, f.target});
      results.failures.push_back(f);
      for (const std::string& shard_variant : results.merged_from) {
        CopyIfPresent(PairMapPath(shard_variant, stem({f.source, f.target})),
                      PairMapPath(results.dir, stem({f.source, f.target})));
      }
    }
    for (const Failure& f : failures) {
      if (f.kind == "shape") results.failures.push_back(f);
    }
    for (const auto& [source, target] : pair_set) {
      results.pairs.push_back({source, target});
      auto it = records.find({source, target});
      results.records.push_back(it == records.end()
                                    ? std::nullopt
                                    : std::optional<PairEvaluation>(std::move(it->second)));
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

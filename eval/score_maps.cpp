#include "eval/score_maps.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <set>

#include "core/errors.h"
#include "core/map_io.h"
#include "core/mesh_io.h"
#include "core/parallel.h"
#include "eval/pair_names.h"

namespace symembed {

bool ScoreMapsOptions::IsValid(std::string* error) const {
  auto fail = [&](const std::string& what) {
    if (error) *error = what;
    return false;
  };
  if (maps_dir.empty()) return fail("maps_dir: must not be empty");
  if (base != 0 && base != 1) return fail("base: must be 0 or 1");
  if (threads < 0) return fail("threads: must be >= 0");
  return true;
}

namespace {

double Seconds(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// What the pairs need of one shape; `error` set when any step failed.
struct LoadedShape {
  const DatasetShape* shape = nullptr;
  int num_input_vertices = 0;
  ShapeGroundTruth truth;
  bool is_target = false;
  EvalShape eval;  // targets only
  std::string error;
  std::map<std::string, double> seconds;
};

void LoadShape(const Dataset& dataset, const PreprocessStage& preprocess, const DatasetMeshLoader& load,
               LoadedShape& s) {
  try {
    auto start = std::chrono::steady_clock::now();
    const Surface input = load ? load(*s.shape) : LoadSurface(s.shape->mesh_path);
    s.num_input_vertices = input.NumVertices();
    s.seconds["load"] = Seconds(start);
    s.truth = dataset.GroundTruth(*s.shape, s.num_input_vertices);
    if (s.is_target) {
      start = std::chrono::steady_clock::now();
      const PreprocessResult pre = preprocess.Run(input);
      s.seconds["preprocess"] = Seconds(start);
      s.eval = MakeEvalShape(pre, input);
    }
  } catch (const std::exception& e) {
    s.error = "shape " + s.shape->name + ": " + e.what();
  }
}

// One warning per plain file name the dataset's pairs cannot use: which pairs it would name and
// where their maps are read from instead.
std::vector<std::string> EscapedNameWarnings(const std::vector<DatasetPair>& pairs,
                                             const PairNames& names) {
  std::map<std::string, std::set<std::pair<std::string, std::string>>> by_plain;
  for (const DatasetPair& p : pairs) {
    if (names.Escaped(p.source, p.target)) {
      by_plain[PlainPairStem(p.source, p.target)].insert({p.source, p.target});
    }
  }
  std::vector<std::string> warnings;
  for (const auto& [plain, group] : by_plain) {
    std::string text = plain + ".map would be ambiguous (" +
                       (group.size() > 1 ? "the name of " + std::to_string(group.size()) + " pairs"
                                         : std::string("it holds '%'")) +
                       "), so the escaped names are read:";
    for (const auto& [source, target] : group) {
      text += " " + source + " -> " + target + " from " + names.Stem(source, target) + ".map;";
    }
    text.back() = ' ';
    warnings.push_back(text + "(docs/usage.md)");
  }
  return warnings;
}

}  // namespace

ScoreMapsResult ScoreMaps(const Dataset& dataset, const PreprocessStage& preprocess,
                          const Evaluator& evaluator, const ScoreMapsOptions& options,
                          const DatasetMeshLoader& load) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("eval options: " + error);
  const auto start = std::chrono::steady_clock::now();
  const DatasetIndex index = dataset.Load();

  struct Job {
    std::string source, target, file;
  };
  // The files are named as a run names its maps (A_B.map unless that is ambiguous), among the
  // dataset's pairs; an ambiguous plain name is not read, since it may be another pair's map.
  const PairNames names(index.pairs);
  std::vector<Job> jobs;
  std::map<std::string, LoadedShape> shapes;
  std::set<std::string> unknown;
  for (const auto& p : index.pairs) {
    Job job{options.reverse ? p.target : p.source, options.reverse ? p.source : p.target,
            options.maps_dir + "/" + names.Stem(p.source, p.target) + ".map"};
    for (const std::string* name : {&job.source, &job.target}) {
      const DatasetShape* shape = index.Find(*name);
      if (!shape) {
        unknown.insert(*name);
        continue;
      }
      shapes[*name].shape = shape;
    }
    if (index.Find(job.target)) shapes[job.target].is_target = true;
    jobs.push_back(std::move(job));
  }

  std::vector<LoadedShape*> to_load;
  for (auto& [name, s] : shapes) to_load.push_back(&s);
  ParallelFor(static_cast<int>(to_load.size()),
              [&](int i) { LoadShape(dataset, preprocess, load, *to_load[i]); }, options.threads);

  ScoreMapsResult result;
  result.warnings = EscapedNameWarnings(index.pairs, names);
  result.pairs.resize(jobs.size());
  std::atomic<int> maps_read{0}, maps_using_zero{0};
  ParallelFor(static_cast<int>(jobs.size()), [&](int i) {
    const Job& job = jobs[i];
    PairEvaluation& out = result.pairs[i];
    auto fail = [&](const std::string& message) {
      out = PairEvaluation{};
      out.source = job.source;
      out.target = job.target;
      out.message = message;
    };
    for (const std::string* name : {&job.source, &job.target}) {
      if (unknown.count(*name)) return fail("shape " + *name + " is not in the dataset");
    }
    const LoadedShape& source = shapes.at(job.source);
    const LoadedShape& target = shapes.at(job.target);
    if (!source.error.empty()) return fail(source.error);
    if (!target.error.empty()) return fail(target.error);
    std::vector<int> map;
    const auto read_start = std::chrono::steady_clock::now();
    try {
      map = ReadMapFile(job.file, options.base, source.num_input_vertices,
                        target.num_input_vertices);
    } catch (const std::exception& e) {
      return fail(e.what());
    }
    if (std::find(map.begin(), map.end(), 0) != map.end()) maps_using_zero.fetch_add(1);
    maps_read.fetch_add(1);
    const double read_seconds = Seconds(read_start);
    out = evaluator.Evaluate(job.source, job.target, target.eval, map,
                             PairGroundTruth(source.truth, source.shape->name, target.truth,
                                                 target.shape->name));
    out.stage_seconds["read_map"] = read_seconds;
  }, options.threads);

  if (options.base == 0 && maps_read > 0 && maps_using_zero == 0) {
    result.warnings.push_back("with --base 0, none of the " + std::to_string(maps_read.load()) +
                              " maps uses target id 0: if they are 1-based, every id is shifted "
                              "by one (use --base 1)");
  }
  SortPairs(result.pairs);
  for (const auto& [name, s] : shapes) result.timings.shape_stage_seconds[name] = s.seconds;
  result.timings.total_seconds = Seconds(start);
  result.timings.peak_rss_mb = PeakRssMb();
  return result;
}

}  // namespace symembed

#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include "apps/args.h"
#include "apps/commands.h"
#include "core/files.h"
#include "core/mesh_io.h"
#include "harness/config.h"
#include "harness/run_evaluation.h"
#include "harness/runner.h"
#include "harness/shards.h"
#include "registry/registry.h"

namespace symembed {
namespace {

// "i/N" with 0 <= i < N.
void ParseShard(const std::string& text, int* index, int* count) {
  const size_t slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    size_t used = 0;
    *index = std::stoi(text.substr(0, slash), &used);
    if (used != slash) throw std::invalid_argument("index");
    const std::string n = text.substr(slash + 1);
    *count = std::stoi(n, &used);
    if (used != n.size()) throw std::invalid_argument("count");
  } catch (const std::exception&) {
    throw UsageError{"--shard: expected i/N (e.g. 0/4), got '" + text + "'"};
  }
  if (*count < 1 || *index < 0 || *index >= *count) {
    throw UsageError{"--shard " + text + ": need 0 <= i < N"};
  }
}

// "stage=n stage=n" of a counter map.
std::string CountsText(const std::map<std::string, int>& counts) {
  std::string text;
  for (const auto& [stage, n] : counts)
    text += (text.empty() ? "" : " ") + stage + "=" + std::to_string(n);
  return text.empty() ? "none" : text;
}

// The marker's command: this run again, resumed, for any shard ({shard}, {out}) of the set.
std::string RerunTemplate(const ArgParser& parser, const std::string& config) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  std::ostringstream c;
  c << "cd " << ShellQuote(fs::current_path().string()) << " && "
    << ShellQuote(ec ? std::string("symembed") : exe.string()) << " run " << ShellQuote(config)
    << " --shard {shard} --shard-by " << parser.Get("shard-by") << " --resume --out {out}";
  for (const char* name : {"variant", "cache", "jobs"}) {
    if (parser.Given(name)) c << " --" << name << " " << ShellQuote(parser.Get(name));
  }
  for (const std::string& set : parser.GetAll("set")) c << " --set " << ShellQuote(set);
  return c.str();
}

// The command's options.
ArgParser RunParser() {
  ArgParser parser(
      "run",
      "Run an experiment: every variant of CONFIG (or one), per-shape stages cached on disk, "
      "pairs in parallel. Writes OUT/<variant>/ (config.yaml, maps/, pairs/, summary.json, "
      "pairs.csv, curve.csv, timings.csv, failures.csv), OUT/comparison.csv and the HTML report "
      "OUT/report/index.html (not for a shard: merge the shards). A failed "
      "shape or pair is recorded in failures.csv and the run goes on. Exit status: 0 when "
      "everything succeeded, 1 when something failed, 2 for usage errors.");
  parser.Option("variant", "run only this variant ('base' is the base pipeline)", "");
  parser.Option("jobs", "worker threads (0: all cores)", "0");
  parser.Switch("resume", "keep the pairs that already have a record in OUT");
  parser.Option("shard",
                "run shard i of N of the pairs (i/N); join shards with merge. The shard folder "
                "gets a shard.txt saying whether it finished",
                "0/1");
  parser.Option(
      "shard-by",
      "how pairs are split into shards: pair (pair index modulo N) or target (all pairs "
      "of a target in one shard, so each target's evaluation distances are computed once)",
      "pair");
  parser.Switch("shapes-only",
                "compute the per-shape stages of shard i of N of the shapes (--shard), for every "
                "variant, into the cache, and write nothing else (symembed slurm runs this first)");
  parser.Option("out", "output folder", "results/<config name>");
  parser.Option("cache", "per-shape cache folder ('' disables it)", "results/.cache");
  parser.Switch("quiet", "no progress on stderr");
  parser.Switch("no-report", "do not write the HTML report (OUT/report; see symembed report)");
  parser.Switch("write-embeddings",
                "also write each shape's canonical embedding (symmetrized, in its frame, on the "
                "preprocessed faces) as OUT/<variant>/embeddings/NAME.off");
  parser.Repeated("set",
                  "override dotted.path=value in the base and every variant; a variant's own "
                  "`set` of the same key wins there, and one that changes the stage's type "
                  "drops its options, with a note; with --variant only that variant is checked "
                  "and such options apply on top (e.g. --variant refined --set "
                  "pipeline.refine.k_end=160)");
  parser.Positionals("CONFIG", "the experiment's YAML file", 1, 1);
  return parser;
}

// The runner's options from the parsed arguments, but for the output folder (it names the
// config). Throws UsageError for arguments that do not go together.
RunOptions RunOptionsOf(const ArgParser& parser) {
  RunOptions options;
  ParseShard(parser.Get("shard"), &options.shard_index, &options.shard_count);
  options.jobs = parser.GetInt("jobs");
  if (options.jobs < 0) throw UsageError{"--jobs: must be >= 0"};
  options.variant = parser.Get("variant");
  options.resume = parser.Flag("resume");
  options.quiet = parser.Flag("quiet");
  options.write_embeddings = parser.Flag("write-embeddings");
  options.cache_dir = parser.Get("cache");
  try {
    options.shard_split = ParseShardSplit(parser.Get("shard-by"));
  } catch (const ConfigError& e) {
    throw UsageError{std::string("--shard-by: ") + e.what()};
  }
  options.shapes_only = parser.Flag("shapes-only");
  if (options.shapes_only) {
    for (const char* name : {"out", "resume", "write-embeddings"}) {
      if (parser.Given(name))
        throw UsageError{std::string("--shapes-only writes no outputs: --") + name +
                         " does not apply"};
    }
    if (options.cache_dir.empty())
      throw UsageError{"--shapes-only needs a --cache folder: the cache is all it writes"};
    if (!options.quiet) {
      options.on_shape = [](const std::string& shape, const std::string& variant,
                            const std::vector<std::string>& computed,
                            const std::string& computed_with) {
        std::string list;
        for (const std::string& stage : computed) list += (list.empty() ? "" : " ") + stage;
        std::string what = list.empty() ? "all stages from the cache" : "computed " + list;
        if (!computed_with.empty()) {
          what = "same mesh bytes as " + computed_with + ", computed with it";
        }
        std::cerr << "symembed run: shape " << shape << " [" << variant << "]: " << what << "\n";
      };
    }
  }
  options.load_mesh = [](const std::string& path) { return LoadSurface(path); };
  return options;
}

// The run's last lines on stderr: warnings, the stages computed, the pairs, the failures.
void PrintRunOutcome(const RunOptions& options, const RunStats& stats,
                     const std::vector<std::string>& warnings) {
  for (const std::string& warning : warnings) {
    std::cerr << "symembed run: warning: " << warning << "\n";
  }
  if (!options.quiet) {
    std::cerr << "symembed run: stages computed: " << CountsText(stats.executed)
              << "; from the cache: " << CountsText(stats.cache_hits);
    if (stats.shapes_shared > 0) {
      std::cerr << "; " << stats.shapes_shared
                << " shapes had the mesh bytes of another and were computed with it";
    }
    std::cerr << "\n";
  }
  if (!options.quiet && options.shapes_only) {
    std::cerr << "symembed run: shard " << options.shard_index << "/" << options.shard_count
              << " of the shapes: " << stats.shapes_computed << " shapes (all variants), "
              << stats.failures.size() << " failures; cache in " << options.cache_dir << "\n";
  } else if (!options.quiet) {
    std::cerr << "symembed run: " << stats.pairs_done << " pairs computed, " << stats.pairs_skipped
              << " kept from an earlier run";
    if (stats.pairs_recomputed > 0) {
      std::cerr << " (" << stats.pairs_recomputed
                << " more had outputs that did not match this run and were computed again)";
    }
    std::cerr << ", " << stats.failures.size() << " failures; outputs in " << options.out_dir
              << "\n";
  }
  if (!stats.ok()) {
    const Failure& first = stats.failures.front();
    std::cerr << "symembed run: " << stats.failures.size() << " failures (first: " << first.kind
              << " " << first.source << (first.target.empty() ? "" : " -> " + first.target)
              << ": " << first.message << ")"
              << (options.shapes_only ? "; the pair runs record them in failures.csv\n"
                                      : "; see failures.csv\n");
  }
}

}  // namespace

int RunCommand(const Args& args) {
  ArgParser parser = RunParser();
  if (!parser.Parse(args)) return 0;
  RunOptions options = RunOptionsOf(parser);

  Registry registry;
  RegisterBuiltinStages(registry);
  const ExperimentConfig config = LoadExperimentConfig(parser.positionals()[0], registry,
                                                       parser.GetAll("set"), options.variant);
  options.out_dir = parser.Given("out") ? parser.Get("out") : "results/" + config.name;
  for (const auto& [variant, line] : config.shadowed_overrides) {
    if (options.variant.empty() || options.variant == variant) {
      std::cerr << "symembed run: note: " << line << "\n";
    }
  }

  // One command writes into a run folder at a time (a --shapes-only run writes only the cache).
  std::optional<FolderLock> lock;
  if (!options.shapes_only) {
    lock.emplace(FolderLock::Acquire(options.out_dir, CommandLine("run", args)));
  }

  // A sharded run says in its folder whether it finished, so that merge can refuse a partial set.
  ShardMarker marker;
  const bool marked = parser.Given("shard") && !options.shapes_only;
  if (marked) {
    marker = {options.shard_index, options.shard_count, options.shard_split, false,
              RerunTemplate(parser, parser.positionals()[0])};
    WriteFileAtomically(ShardMarkerPath(options.out_dir), FormatShardMarker(marker));
  }
  GroundTruthRunEvaluation evaluation(&registry);
  const RunStats stats = RunExperiment(config, registry, options, evaluation);
  if (marked) {
    marker.complete = true;
    WriteFileAtomically(ShardMarkerPath(options.out_dir), FormatShardMarker(marker));
  }
  std::vector<std::string> warnings = stats.warnings;
  warnings.insert(warnings.end(), evaluation.warnings().begin(), evaluation.warnings().end());
  PrintRunOutcome(options, stats, warnings);
  if (!parser.Flag("no-report") && options.shard_count == 1 && !options.shapes_only) {
    ReportAfterCommand("run", options.out_dir, registry);
  }
  return stats.ok() ? 0 : 1;
}

}  // namespace symembed

#include <iostream>

#include "apps/args.h"
#include "apps/commands.h"
#include "core/files.h"
#include "harness/merge.h"
#include "harness/run_evaluation.h"
#include "harness/runner.h"
#include "harness/shards.h"

namespace symembed {
namespace {

// Says which shards to rerun and how; `hint` ({shards}: their indices) is printed last.
void ReportUnfinished(const std::vector<UnfinishedShard>& unfinished, int count,
                      const std::string& hint) {
  std::cerr << "symembed merge: " << unfinished.size() << " of " << count
            << " shards did not finish; nothing was merged:\n";
  const std::string of = "/" + std::to_string(count);
  for (const UnfinishedShard& s : unfinished) {
    std::cerr << "  shard " << (s.index < 0 ? "?" : std::to_string(s.index)) << of
              << (s.dir.empty() ? "" : " (" + s.dir + ")") << ": " << s.reason << "\n";
  }
  std::cerr << "rerun them (a rerun keeps the pairs already done), then merge again:\n";
  for (const UnfinishedShard& s : unfinished) {
    if (!s.command.empty()) {
      std::cerr << "  " << s.command << "\n";
    } else {
      std::cerr << "  shard " << (s.index < 0 ? "?" : std::to_string(s.index)) << of
                << ": symembed run CONFIG --shard " << (s.index < 0 ? "i" : std::to_string(s.index))
                << of << " --out DIR, with the options of the other shards\n";
    }
  }
  if (!hint.empty()) {
    std::string text = hint;
    const std::string list = ShardIndexList(unfinished);
    for (size_t at = text.find("{shards}"); at != std::string::npos;
         at = text.find("{shards}", at + list.size())) {
      text.replace(at, 8, list);
    }
    std::cerr << text << "\n";
  }
}

}  // namespace

int MergeCommand(const Args& args) {
  ArgParser parser(
      "merge",
      "Join the output folders of sharded runs (symembed run --shard i/N --out SHARD_DIR) into "
      "the outputs a single run writes: maps, per-pair records, failures.csv, then summaries "
      "and comparison recomputed from the records, and the HTML report OUT/report/index.html. "
      "Shard folders of runs made with --shard must form a finished set (each shard.txt says "
      "complete, every index once); otherwise nothing is merged and the shards to rerun are "
      "listed with their commands. Exit status: 1 when the merged run has failures, 3 when "
      "shards did not finish, else 0.");
  parser.Option("out", "output folder (required)", "");
  parser.Switch("no-report", "do not write the HTML report (see symembed report)");
  parser.Option("rerun-hint",
                "printed after the list of unfinished shards, with {shards} replaced by their "
                "indices, comma-separated (symembed slurm passes the sbatch command)",
                "");
  parser.Positionals("SHARD_DIR...", "output folders of the shards", 1, -1);
  if (!parser.Parse(args)) return 0;
  if (!parser.Given("out") || parser.Get("out").empty()) throw UsageError{"--out is required"};
  const ShardSetCheck check = CheckShardSet(parser.positionals());
  if (!check.unfinished.empty()) {
    ReportUnfinished(check.unfinished, check.count, parser.Get("rerun-hint"));
    return 3;
  }
  const FolderLock lock = FolderLock::Acquire(parser.Get("out"), CommandLine("merge", args));
  GroundTruthRunEvaluation evaluation;
  const std::vector<Failure> failures =
      MergeRuns(parser.positionals(), parser.Get("out"), evaluation);
  for (const std::string& warning : evaluation.warnings()) {
    std::cerr << "symembed merge: warning: " << warning << "\n";
  }
  std::cerr << "symembed merge: " << parser.positionals().size() << " folders merged into "
            << parser.Get("out") << "\n";
  if (!failures.empty()) {
    std::cerr << "symembed merge: " << failures.size() << " failures; see failures.csv\n";
  }
  if (!parser.Flag("no-report")) {
    Registry registry;
    RegisterBuiltinStages(registry);
    ReportAfterCommand("merge", parser.Get("out"), registry);
  }
  return failures.empty() ? 0 : 1;
}

}  // namespace symembed

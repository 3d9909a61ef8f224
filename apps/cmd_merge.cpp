#include <iostream>

#include "apps/args.h"
#include "apps/commands.h"
#include "eval/run_evaluation.h"
#include "registry/merge.h"
#include "registry/runner.h"

namespace symembed {

int MergeCommand(const Args& args) {
  ArgParser parser(
      "merge",
      "Join the output folders of sharded runs (symembed run --shard i/N --out SHARD_DIR) into "
      "the outputs a single run writes: maps, per-pair records, failures.csv, then summaries "
      "and comparison recomputed from the records, and the HTML report OUT/report/index.html. "
      "Exit status: 1 when the merged run has "
      "failures, else 0.");
  parser.Option("out", "output folder (required)", "");
  parser.Switch("no-report", "do not write the HTML report (see symembed report)");
  parser.Positionals("SHARD_DIR...", "output folders of the shards", 1, -1);
  if (!parser.Parse(args)) return 0;
  if (!parser.Given("out") || parser.Get("out").empty()) throw UsageError{"--out is required"};
  GroundTruthRunEvaluation evaluation;
  const std::vector<Failure> failures =
      MergeRuns(parser.positionals(), parser.Get("out"), evaluation);
  for (const std::string& warning : evaluation.warnings()) {
    std::cerr << "symembed merge: warning: " << warning << "\n";
  }
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

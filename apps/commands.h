// The symembed subcommands. Each takes its arguments (after the subcommand name) and returns
// the process exit code; usage errors throw UsageError (exit 2), other errors symembed::Error
// (exit 1, one line on stderr).
#pragma once

#include <string>
#include <vector>

#include "registry/registry.h"

namespace symembed {

using Args = std::vector<std::string>;

int RunCommand(const Args& args);       // run CONFIG: run an experiment
int EvalCommand(const Args& args);      // eval: score a folder of maps
int CheckCommand(const Args& args);     // check SUMMARY --baseline FILE
int MergeCommand(const Args& args);     // merge DIR...: join shard outputs
int SlurmCommand(const Args& args);     // slurm CONFIG --shards N: sbatch jobs of a study
int StagesCommand(const Args& args);    // stages: list registered stages
int SynthCommand(const Args& args);     // synth: write a synthetic dataset
int RemeshCommand(const Args& args);    // remesh --in ROOT --out DIR: a remeshed dataset
int ValidateCommand(const Args& args);  // validate MESH...: mesh validation report
int ReportCommand(const Args& args);    // report RESULTS_DIR: the HTML report

// The end of run, merge and eval (unless --no-report): writes RESULTS_DIR/report and prints its
// path, or a warning when it could not be written (never an error: the CSVs are the results).
void ReportAfterCommand(const std::string& command, const std::string& results_dir,
                        const Registry& registry);

}  // namespace symembed

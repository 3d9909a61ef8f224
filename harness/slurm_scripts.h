// The batch scripts of `symembed slurm` (docs/cluster.md): a study run on a Slurm cluster as
// three jobs, written to OUT/slurm/ together with the script that submits them.
//
//   shapes.sbatch  array of shape_tasks tasks; task i runs
//                  `symembed run CONFIG --shapes-only --shard i/shape_tasks`: the per-shape
//                  stages of every variant for its shapes, into the shared cache, so that no
//                  shape is computed by two tasks
//   pairs.sbatch   array of pair_tasks tasks, after the shapes job; task i runs
//                  `symembed run CONFIG --shard i/pair_tasks --shard-by SPLIT --resume
//                  --out OUT/shards/i`, which finds every shape in the cache
//   merge.sbatch   after the pairs job: `symembed merge --out OUT OUT/shards/0 ...`, which
//                  refuses a set with an unfinished shard and names the tasks to rerun
//   submit.sh      submits the three (`sbatch --parsable`, each later job
//                  `--dependency=afterany:` on the one before, so a failed task is reported by
//                  the merge instead of leaving the jobs after it pending forever) and prints
//                  "shapes job ID", "pairs job ID", "merge job ID"; `submit.sh --rerun 1,3`
//                  submits pair tasks 1 and 3 again (they resume) and a merge after them
// Logs: OUT/slurm/logs/shapes-I.log, pairs-I.log, merge.log (appended to on a rerun).
#pragma once

#include <string>
#include <vector>

#include "harness/shards.h"

namespace symembed {

struct SlurmOptions {
  std::string binary;     // the symembed executable the jobs run (absolute path)
  std::string config;     // the experiment's YAML file (absolute path)
  std::string workdir;    // the jobs' working folder, where the config's relative paths start
  std::string out_dir;    // OUT (absolute path)
  std::string cache_dir;  // the per-shape cache all tasks share (absolute path)
  std::string job_name = "symembed";       // prefix of the jobs' names: [A-Za-z0-9_.-]+
  int shape_tasks = 1;                     // tasks of the shapes array, >= 1
  int pair_tasks = 1;                      // tasks of the pairs array, >= 1
  ShardSplit split = ShardSplit::kTarget;  // how the pair tasks split the pairs
  int cpus = 1;                            // CPUs per task (each task runs that many threads), >= 1
  std::string partition;                   // --partition; empty: the cluster's default
  std::string time;                        // --time limit per task, e.g. 1:00:00; empty: default
  std::string mem;                         // --mem per task, e.g. 8G; empty: default
  std::string variant;                     // run only this variant; empty: all
  std::vector<std::string> sets;           // --set overrides (dotted.path=value)
  std::vector<std::string> sbatch_args;    // more #SBATCH options, each "--name[=value]"

  // False with *error naming the field and what is wrong: a path that is not absolute or
  // holds a double quote or a line break (paths stand double-quoted in #SBATCH lines), a
  // count < 1, a partition, time, memory or sbatch option with white space, ...
  bool IsValid(std::string* error) const;
};

struct SlurmScripts {
  std::string shapes;  // shapes.sbatch
  std::string pairs;   // pairs.sbatch
  std::string merge;   // merge.sbatch
  std::string submit;  // submit.sh
};

// OUT/slurm, where the scripts go, and OUT/slurm/logs.
std::string SlurmScriptDir(const std::string& out_dir);
std::string SlurmLogDir(const std::string& out_dir);
// OUT/shards/I, the folder of pair task I.
std::string SlurmShardDir(const std::string& out_dir, int index);

// The texts of the scripts. Throws ConfigError with IsValid's message when options are not.
SlurmScripts MakeSlurmScripts(const SlurmOptions& options);

}  // namespace symembed

// `symembed merge`: the output folders of sharded runs joined into one, equal to a single run.
#pragma once

#include <string>
#include <vector>

#include "harness/runner.h"

namespace symembed {

// Joins the output folders of sharded runs (each an out_dir of RunExperiment) into out_dir:
// copies every variant's config.yaml (which must agree), maps, pair and shape records (their
// file stems taken among all the shards' pairs of the variant, as the runs named them), merges
// failures, then writes the summaries as a single run would; each merged variant folder holds
// IN_PROGRESS until its summary is written. Throws InvalidInputError naming the folder when a
// shard's variant folder is in progress (its run did not finish), IoError.
// Returns the merged failures.
std::vector<Failure> MergeRuns(const std::vector<std::string>& shard_dirs,
                               const std::string& out_dir, RunEvaluation& evaluation);

}  // namespace symembed

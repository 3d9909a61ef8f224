// Per-shape work once per mesh content: the dataset shapes whose mesh files hold identical bytes
// (a null shape linked under the name of every pair it is in, a copy under another name) are
// one computation, whose outcome each of them then receives under its own name.
//
// Everything about a name stays that name's: its ground truth and the shapes.csv measures
// against it, its failure (a failure of the shared computation is one per name, each naming
// the name's own file), its warnings. The names after the first are reported as cache hits are:
// every stage time marked cached, with the seconds of the computation.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "harness/cache.h"
#include "harness/shape_pipeline.h"
#include "registry/dataset.h"

namespace symembed {

struct ContentGroup {
  std::vector<std::string> names;  // in the order they were given
  // MeshKey of their files; unset for a single name whose file cannot be read (its computation
  // then fails as loading it does) or that the dataset does not have.
  std::optional<uint64_t> mesh_key;
};

// `names` grouped by the MeshKey of their files, groups in order of their first name. Hashes
// the files on up to `jobs` threads (0: all cores).
std::vector<ContentGroup> GroupByContent(const std::vector<std::string>& names,
                                         const DatasetIndex& index, int jobs);

// The groups a shapes-only shard computes (runner.h): those whose first name is one of
// ShapesOfShard(sorted_names, index, count), so that no content is computed by two shards.
std::vector<ContentGroup> ContentGroupsOfShard(const std::vector<std::string>& sorted_names,
                                               const DatasetIndex& dataset, int index, int count,
                                               int jobs);

// What one name of a group came to: its outcome, or its failure.
struct NamedOutcome {
  std::unique_ptr<ShapeOutcome> outcome;  // null when the name failed
  std::string failure;                    // the message, naming the name's own mesh file
  // The outcome is that of the group's first name that reached the stages (computed_with), not
  // a computation of its own.
  bool reused = false;
  std::string computed_with;
};

// Loads the group's mesh once, reads each name's ground truth, runs the per-shape stages once
// for the names whose ground truth was read, and gives each name its outcome (OutcomeOfShape).
// Returns one entry per name of the group, in its order; never throws what loading, the
// dataset or a stage throws. context.counters counts the stages run or loaded.
std::vector<NamedOutcome> ComputeContentGroup(const ContentGroup& group, const DatasetIndex& index,
                                              const Pipeline& pipeline, const MeshLoader& load_mesh,
                                              const ShapeContext& context);

// `message`, from work on the file `computed_path`, as the failure of the shape whose file is
// `path`: naming `path` in front (in place of computed_path when the message starts with it).
std::string FailureNamingFile(const std::string& message, const std::string& computed_path,
                              const std::string& path);

}  // namespace symembed

// A run split over processes or machines (`symembed run --shard i/N`, `--shapes-only`,
// `symembed slurm`, docs/cluster.md): which pairs and shapes a shard takes, and the marker file
// that says whether a shard finished, which `symembed merge` checks before it joins shards.
//
// The marker OUT/shard.txt of a run made with --shard is written when the run starts
// (`status: running`) and again when it ends (`status: complete`), one "key: value" per line:
//   shard: 1/4
//   split: target
//   status: complete
//   command: cd '/home/me' && '/opt/symembed' run 'study.yaml' --shard {shard} ... --out {out}
// `command` resumes the shard when {shard} is replaced by "1/4" and {out} by its folder (shell
// quoted); it is written by the command line, so the marker can name the exact command to rerun.
#pragma once

#include <string>
#include <vector>

#include "registry/dataset.h"

namespace symembed {

// How the pairs of a run are split into shards.
enum class ShardSplit {
  kPair,    // pair i (in (source, target) order) goes to shard i mod N: balanced to one pair
  kTarget,  // all pairs of a target go to one shard, so the evaluation's distances on a target
            // (computed once per target and shared by its pairs) are computed by one shard only
};

// "pair" or "target"; throws ConfigError naming the valid values.
ShardSplit ParseShardSplit(const std::string& text);
const char* ShardSplitName(ShardSplit split);

// The pairs sorted by (source, target), without duplicates: the order shards are cut from.
std::vector<DatasetPair> SortedPairs(std::vector<DatasetPair> pairs);

// The shard, in [0, count), of each of `pairs` (sorted by (source, target), no duplicates).
// kTarget assigns targets in decreasing order of their pair count (ties: by name) each to the
// shard with the fewest pairs so far (ties: the lowest index). Throws ConfigError when
// count < 1.
std::vector<int> PairShards(const std::vector<DatasetPair>& pairs, ShardSplit split, int count);

// The largest shard count that leaves no shard without pairs: #pairs for kPair, #distinct
// targets for kTarget (0 for no pairs).
int MaxPairShards(const std::vector<DatasetPair>& pairs, ShardSplit split);

// The shapes shard `index` of `count` computes in a shapes-only run: the names (sorted, no
// duplicates) whose position is index modulo count, so every shape is in exactly one shard.
std::vector<std::string> ShapesOfShard(const std::vector<std::string>& sorted_names, int index,
                                       int count);

// The shapes of the pairs, sorted, without duplicates.
std::vector<std::string> ShapesOfPairs(const std::vector<DatasetPair>& pairs);

struct ShardMarker {
  int index = 0;
  int count = 1;
  ShardSplit split = ShardSplit::kPair;
  bool complete = false;
  std::string command;  // template with {shard} and {out}; may be empty
};

// OUT/shard.txt.
std::string ShardMarkerPath(const std::string& out_dir);
std::string FormatShardMarker(const ShardMarker& marker);
// Throws InvalidInputError naming `where` and what is wrong.
ShardMarker ParseShardMarker(const std::string& text, const std::string& where);

// marker.command with {shard} = "index/count" and {out} = the shell-quoted out_dir.
std::string ShardCommand(const ShardMarker& marker, int index, const std::string& out_dir);

// A shard that is missing from, or did not finish in, a set of shard folders.
struct UnfinishedShard {
  int index = -1;       // -1 when it cannot be told
  std::string dir;      // the folder given for it; empty when none was
  std::string reason;   // e.g. "started but did not finish"
  std::string command;  // the command that (re)runs it; empty when unknown
};

struct ShardSetCheck {
  int count = 0;  // the shard count of the markers; 0 when no folder has one
  std::vector<UnfinishedShard> unfinished;  // by index
};

// Checks that shard_dirs hold one finished shard set: every folder has a complete marker, all
// with the same count and split, every index in [0, count) exactly once. Folders without a
// marker are matched in order with the indices no marker claims (a shard that never started
// has none). When no folder has a marker at all (runs made without --shard, e.g. one per
// variant), there is nothing to check: count 0, nothing unfinished. Throws InvalidInputError
// when markers disagree (count, split, an index given twice) or one cannot be parsed.
ShardSetCheck CheckShardSet(const std::vector<std::string>& shard_dirs);

// The indices of the shards, comma-separated ("1,3"; the form of `sbatch --array`).
std::string ShardIndexList(const std::vector<UnfinishedShard>& shards);

// `text` quoted for a POSIX shell: unchanged when it holds only [A-Za-z0-9_./:=@%+,-], else
// between single quotes ('\'' for a quote).
std::string ShellQuote(const std::string& text);

}  // namespace symembed

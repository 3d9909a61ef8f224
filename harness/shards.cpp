#include "harness/shards.h"

#include <algorithm>
#include <map>
#include <optional>
#include <set>
#include <sstream>
#include <tuple>

#include "core/errors.h"
#include "core/files.h"

namespace symembed {

ShardSplit ParseShardSplit(const std::string& text) {
  if (text == "pair") return ShardSplit::kPair;
  if (text == "target") return ShardSplit::kTarget;
  throw ConfigError("shard split '" + text + "': expected one of pair, target");
}

const char* ShardSplitName(ShardSplit split) {
  return split == ShardSplit::kPair ? "pair" : "target";
}

std::vector<DatasetPair> SortedPairs(std::vector<DatasetPair> pairs) {
  auto key = [](const DatasetPair& p) { return std::tie(p.source, p.target); };
  std::sort(pairs.begin(), pairs.end(),
            [&](const DatasetPair& a, const DatasetPair& b) { return key(a) < key(b); });
  pairs.erase(
      std::unique(pairs.begin(), pairs.end(),
                  [&](const DatasetPair& a, const DatasetPair& b) { return key(a) == key(b); }),
      pairs.end());
  return pairs;
}

std::vector<int> PairShards(const std::vector<DatasetPair>& pairs, ShardSplit split, int count) {
  if (count < 1) throw ConfigError("shard count " + std::to_string(count) + ": must be >= 1");
  std::vector<int> shard(pairs.size(), 0);
  if (split == ShardSplit::kPair) {
    for (size_t i = 0; i < pairs.size(); ++i) shard[i] = static_cast<int>(i % count);
    return shard;
  }
  std::map<std::string, int> pairs_of_target;
  for (const DatasetPair& p : pairs) ++pairs_of_target[p.target];
  std::vector<std::pair<std::string, int>> targets(pairs_of_target.begin(), pairs_of_target.end());
  // Largest first onto the least loaded shard (greedy LPT): within 4/3 of the best balance, and
  // deterministic, so every shard of a run computes the same assignment on its own.
  std::stable_sort(targets.begin(), targets.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  std::vector<int> load(count, 0);
  std::map<std::string, int> shard_of_target;
  for (const auto& [name, n] : targets) {
    const int s = static_cast<int>(std::min_element(load.begin(), load.end()) - load.begin());
    shard_of_target[name] = s;
    load[s] += n;
  }
  for (size_t i = 0; i < pairs.size(); ++i) shard[i] = shard_of_target.at(pairs[i].target);
  return shard;
}

int MaxPairShards(const std::vector<DatasetPair>& pairs, ShardSplit split) {
  if (split == ShardSplit::kPair) return static_cast<int>(pairs.size());
  std::set<std::string> targets;
  for (const DatasetPair& p : pairs) targets.insert(p.target);
  return static_cast<int>(targets.size());
}

std::vector<std::string> ShapesOfShard(const std::vector<std::string>& sorted_names, int index,
                                       int count) {
  std::vector<std::string> names;
  for (size_t i = 0; i < sorted_names.size(); ++i) {
    if (static_cast<int>(i % count) == index) names.push_back(sorted_names[i]);
  }
  return names;
}

std::vector<std::string> ShapesOfPairs(const std::vector<DatasetPair>& pairs) {
  std::set<std::string> names;
  for (const DatasetPair& p : pairs) {
    names.insert(p.source);
    names.insert(p.target);
  }
  return {names.begin(), names.end()};
}

std::string ShardMarkerPath(const std::string& out_dir) { return out_dir + "/shard.txt"; }

std::string FormatShardMarker(const ShardMarker& marker) {
  std::ostringstream out;
  out << "shard: " << marker.index << "/" << marker.count << "\n"
      << "split: " << ShardSplitName(marker.split) << "\n"
      << "status: " << (marker.complete ? "complete" : "running") << "\n";
  if (!marker.command.empty()) out << "command: " << marker.command << "\n";
  return out.str();
}

ShardMarker ParseShardMarker(const std::string& text, const std::string& where) {
  ShardMarker marker;
  std::set<std::string> seen;
  std::istringstream in(text);
  int line_number = 0;
  for (std::string line; std::getline(in, line);) {
    ++line_number;
    if (line.empty()) continue;
    const std::string at = where + ":" + std::to_string(line_number) + ": ";
    const size_t colon = line.find(": ");
    if (colon == std::string::npos) throw InvalidInputError(at + "expected 'key: value'");
    const std::string key = line.substr(0, colon), value = line.substr(colon + 2);
    seen.insert(key);
    if (key == "shard") {
      char slash = 0;
      std::istringstream v(value);
      if (!(v >> marker.index >> slash >> marker.count) || slash != '/' || !v.eof() ||
          marker.count < 1 || marker.index < 0 || marker.index >= marker.count) {
        throw InvalidInputError(at + "shard: expected i/N with 0 <= i < N, got '" + value + "'");
      }
    } else if (key == "split") {
      try {
        marker.split = ParseShardSplit(value);
      } catch (const ConfigError& e) {
        throw InvalidInputError(at + e.what());
      }
    } else if (key == "status") {
      if (value != "running" && value != "complete") {
        throw InvalidInputError(at + "status: expected running or complete, got '" + value + "'");
      }
      marker.complete = value == "complete";
    } else if (key == "command") {
      marker.command = value;
    } else {
      throw InvalidInputError(at + "unknown key '" + key +
                              "' (known: shard, split, status, command)");
    }
  }
  for (const char* key : {"shard", "split", "status"}) {
    if (!seen.count(key)) throw InvalidInputError(where + ": no '" + key + "' line");
  }
  return marker;
}

namespace {

void ReplaceAll(std::string* text, const std::string& from, const std::string& to) {
  for (size_t at = text->find(from); at != std::string::npos;
       at = text->find(from, at + to.size())) {
    text->replace(at, from.size(), to);
  }
}

}  // namespace

std::string ShardCommand(const ShardMarker& marker, int index, const std::string& out_dir) {
  std::string command = marker.command;
  ReplaceAll(&command, "{shard}", std::to_string(index) + "/" + std::to_string(marker.count));
  ReplaceAll(&command, "{out}", ShellQuote(out_dir));
  return command;
}

ShardSetCheck CheckShardSet(const std::vector<std::string>& shard_dirs) {
  std::vector<std::optional<ShardMarker>> markers;
  const ShardMarker* first = nullptr;
  std::string first_dir;
  for (const std::string& dir : shard_dirs) {
    auto text = ReadFileBytes(ShardMarkerPath(dir));
    markers.push_back(
        text ? std::optional<ShardMarker>(ParseShardMarker(*text, ShardMarkerPath(dir)))
             : std::nullopt);
  }
  std::map<int, size_t> dir_of_index;
  for (size_t i = 0; i < markers.size(); ++i) {
    if (!markers[i]) continue;
    const ShardMarker& m = *markers[i];
    if (!first) {
      first = &m;
      first_dir = shard_dirs[i];
    } else if (m.count != first->count || m.split != first->split) {
      throw InvalidInputError(ShardMarkerPath(shard_dirs[i]) + ": shard " +
                              std::to_string(m.index) + "/" + std::to_string(m.count) + " split " +
                              ShardSplitName(m.split) + " does not belong with " +
                              ShardMarkerPath(first_dir) + " (" + std::to_string(first->count) +
                              " shards split by " + ShardSplitName(first->split) + ")");
    }
    if (!dir_of_index.emplace(m.index, i).second) {
      throw InvalidInputError(shard_dirs[i] + " and " + shard_dirs[dir_of_index[m.index]] +
                              " are both shard " + std::to_string(m.index) + "/" +
                              std::to_string(m.count));
    }
  }
  ShardSetCheck check;
  if (!first) return check;
  check.count = first->count;
  std::vector<UnfinishedShard>& unfinished = check.unfinished;
  std::vector<int> unclaimed;
  for (int k = 0; k < first->count; ++k) {
    if (!dir_of_index.count(k)) unclaimed.push_back(k);
  }
  size_t next_unclaimed = 0;
  for (size_t i = 0; i < markers.size(); ++i) {
    UnfinishedShard shard;
    shard.dir = shard_dirs[i];
    if (markers[i]) {
      if (markers[i]->complete) continue;
      shard.index = markers[i]->index;
      shard.reason = "started but did not finish";
      shard.command = ShardCommand(*markers[i], shard.index, shard.dir);
    } else {
      shard.reason = "never started (no " + ShardMarkerPath(shard.dir) + ")";
      if (next_unclaimed < unclaimed.size()) {
        shard.index = unclaimed[next_unclaimed++];
        shard.command = ShardCommand(*first, shard.index, shard.dir);
      }
    }
    unfinished.push_back(shard);
  }
  for (; next_unclaimed < unclaimed.size(); ++next_unclaimed) {
    UnfinishedShard shard;
    shard.index = unclaimed[next_unclaimed];
    shard.reason = "no folder given for it";
    unfinished.push_back(shard);
  }
  std::stable_sort(
      unfinished.begin(), unfinished.end(),
      [](const UnfinishedShard& a, const UnfinishedShard& b) { return a.index < b.index; });
  return check;
}

std::string ShardIndexList(const std::vector<UnfinishedShard>& shards) {
  std::string list;
  for (const UnfinishedShard& s : shards) {
    if (s.index >= 0) list += (list.empty() ? "" : ",") + std::to_string(s.index);
  }
  return list;
}

std::string ShellQuote(const std::string& text) {
  static const std::string kSafe =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_./:=@%+,-";
  if (!text.empty() && text.find_first_not_of(kSafe) == std::string::npos) return text;
  std::string quoted = "'";
  for (char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace symembed

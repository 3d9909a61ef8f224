#include "harness/shards.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

#include "core/errors.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::TempDir;
using testing::WriteText;

// Every ordered pair within two classes of 4 shapes: 24 pairs, 8 targets of 3 pairs each.
std::vector<DatasetPair> TwoClasses() {
  std::vector<DatasetPair> pairs;
  for (const char* c : {"a", "b"}) {
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        if (i != j) pairs.push_back({c + std::to_string(i), c + std::to_string(j)});
      }
    }
  }
  return SortedPairs(pairs);
}

TEST(PairShards, PairSplitIsTheIndexModuloTheCount) {
  const std::vector<int> shard = PairShards(TwoClasses(), ShardSplit::kPair, 5);
  for (size_t i = 0; i < shard.size(); ++i) EXPECT_EQ(shard[i], static_cast<int>(i % 5));
  EXPECT_THROW(PairShards(TwoClasses(), ShardSplit::kPair, 0), ConfigError);
}

TEST(PairShards, TargetSplitKeepsEachTargetInOneShardAndBalancesThePairs) {
  const std::vector<DatasetPair> pairs = TwoClasses();
  const std::vector<int> shard = PairShards(pairs, ShardSplit::kTarget, 3);
  std::map<std::string, std::set<int>> shards_of_target;
  std::vector<int> load(3, 0);
  for (size_t i = 0; i < pairs.size(); ++i) {
    ASSERT_GE(shard[i], 0);
    ASSERT_LT(shard[i], 3);
    shards_of_target[pairs[i].target].insert(shard[i]);
    ++load[shard[i]];
  }
  for (const auto& [target, shards] : shards_of_target) EXPECT_EQ(shards.size(), 1u) << target;
  // 8 targets of 3 pairs on 3 shards: 3, 3 and 2 targets.
  EXPECT_EQ(load, (std::vector<int>{9, 9, 6}));
  EXPECT_EQ(MaxPairShards(pairs, ShardSplit::kTarget), 8);
  EXPECT_EQ(MaxPairShards(pairs, ShardSplit::kPair), 24);
}

// Uneven targets: the greedy assignment puts the largest target alone.
TEST(PairShards, TargetSplitPutsLargeTargetsFirst) {
  const std::vector<DatasetPair> pairs = SortedPairs({{"a", "t"},
                                                      {"b", "t"},
                                                      {"c", "t"},
                                                      {"d", "t"},
                                                      {"a", "u"},
                                                      {"b", "u"},
                                                      {"a", "v"},
                                                      {"b", "v"}});
  const std::vector<int> shard = PairShards(pairs, ShardSplit::kTarget, 2);
  std::vector<int> load(2, 0);
  for (int s : shard) ++load[s];
  EXPECT_EQ(load, (std::vector<int>{4, 4}));
}

TEST(ShapesOfShard, ShardsPartitionTheShapes) {
  const std::vector<std::string> names = ShapesOfPairs(TwoClasses());
  ASSERT_EQ(names.size(), 8u);
  std::multiset<std::string> seen;
  for (int i = 0; i < 3; ++i) {
    for (const std::string& n : ShapesOfShard(names, i, 3)) seen.insert(n);
  }
  EXPECT_EQ(seen, std::multiset<std::string>(names.begin(), names.end()));
  EXPECT_EQ(ShapesOfShard(names, 2, 3), (std::vector<std::string>{"a2", "b1"}));
  EXPECT_TRUE(ShapesOfShard(names, 9, 10).empty());  // more shards than shapes
}

TEST(ShardMarker, FormatsAndParsesBackAndNamesTheLineOfAnError) {
  const ShardMarker marker{2, 4, ShardSplit::kTarget, true,
                           "cd /w && symembed run c.yaml --shard {shard} --out {out}"};
  const std::string text = FormatShardMarker(marker);
  EXPECT_EQ(text,
            "shard: 2/4\nsplit: target\nstatus: complete\n"
            "command: cd /w && symembed run c.yaml --shard {shard} --out {out}\n");
  const ShardMarker back = ParseShardMarker(text, "s/shard.txt");
  EXPECT_EQ(back.index, 2);
  EXPECT_EQ(back.count, 4);
  EXPECT_EQ(back.split, ShardSplit::kTarget);
  EXPECT_TRUE(back.complete);
  EXPECT_EQ(ShardCommand(back, 3, "/o/my shards/3"),
            "cd /w && symembed run c.yaml --shard 3/4 --out '/o/my shards/3'");
  try {
    ParseShardMarker("shard: 4/4\nsplit: pair\nstatus: running\n", "s/shard.txt");
    FAIL() << "expected an error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("s/shard.txt:1: shard"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParseShardMarker("shard: 1/4\nsplit: pair\n", "x"), InvalidInputError);
  EXPECT_THROW(ParseShardMarker("shard: 1/4\nsplit: pair\nstatus: done\n", "x"), InvalidInputError);
}

class ShardSetTest : public ::testing::Test {
 protected:
  std::string Shard(int index, int count, bool complete) {
    const std::string dir = tmp_.File("shards/" + std::to_string(index));
    WriteText(ShardMarkerPath(dir),
              FormatShardMarker({index, count, ShardSplit::kTarget, complete,
                                 "symembed run c.yaml --shard {shard} --resume --out {out}"}));
    return dir;
  }
  TempDir tmp_;
};

TEST_F(ShardSetTest, AFinishedSetHasNothingUnfinished) {
  const ShardSetCheck check =
      CheckShardSet({Shard(0, 3, true), Shard(1, 3, true), Shard(2, 3, true)});
  EXPECT_EQ(check.count, 3);
  EXPECT_TRUE(check.unfinished.empty());
}

TEST_F(ShardSetTest, NamesTheShardsThatDidNotFinishWithTheirCommands) {
  const std::string never = tmp_.File("shards/3");  // never started: no folder at all
  const ShardSetCheck check =
      CheckShardSet({Shard(0, 4, true), Shard(1, 4, false), Shard(2, 4, true), never});
  EXPECT_EQ(check.count, 4);
  ASSERT_EQ(check.unfinished.size(), 2u);
  EXPECT_EQ(check.unfinished[0].index, 1);
  EXPECT_EQ(check.unfinished[0].reason, "started but did not finish");
  EXPECT_EQ(check.unfinished[0].command,
            "symembed run c.yaml --shard 1/4 --resume --out " + ShellQuote(tmp_.File("shards/1")));
  EXPECT_EQ(check.unfinished[1].index, 3);
  EXPECT_EQ(check.unfinished[1].dir, never);
  EXPECT_NE(check.unfinished[1].reason.find("never started"), std::string::npos);
  EXPECT_EQ(check.unfinished[1].command,
            "symembed run c.yaml --shard 3/4 --resume --out " + ShellQuote(never));
  EXPECT_EQ(ShardIndexList(check.unfinished), "1,3");
}

TEST_F(ShardSetTest, AShardLeftOffTheListIsNamed) {
  const ShardSetCheck check = CheckShardSet({Shard(0, 3, true), Shard(2, 3, true)});
  ASSERT_EQ(check.unfinished.size(), 1u);
  EXPECT_EQ(check.unfinished[0].index, 1);
  EXPECT_EQ(check.unfinished[0].reason, "no folder given for it");
}

TEST_F(ShardSetTest, MismatchedOrRepeatedShardsAreErrorsAndUnmarkedFoldersAreNotChecked) {
  EXPECT_THROW(CheckShardSet({Shard(0, 2, true), Shard(1, 3, true)}), InvalidInputError);
  EXPECT_THROW(CheckShardSet({Shard(0, 2, true), Shard(0, 2, true)}), InvalidInputError);
  const ShardSetCheck none = CheckShardSet({tmp_.File("a"), tmp_.File("b")});
  EXPECT_EQ(none.count, 0);
  EXPECT_TRUE(none.unfinished.empty());
}

TEST(ShellQuote, QuotesOnlyWhatTheShellWouldSplitOrExpand) {
  EXPECT_EQ(ShellQuote("/a/b-c_d.yaml"), "/a/b-c_d.yaml");
  EXPECT_EQ(ShellQuote("/my data/x"), "'/my data/x'");
  EXPECT_EQ(ShellQuote("it's"), "'it'\\''s'");
  EXPECT_EQ(ShellQuote("$HOME"), "'$HOME'");
  EXPECT_EQ(ShellQuote(""), "''");
}

}  // namespace
}  // namespace symembed

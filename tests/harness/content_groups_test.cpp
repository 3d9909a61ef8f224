#include "harness/content_groups.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <sstream>

#include "harness/config.h"
#include "harness/run_outputs.h"
#include "harness/runner.h"
#include "tests/harness/runner_fixture.h"

namespace symembed {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;
using testing::TempDir;
using testing::WriteText;
using testing::runner::RunConfig;
using testing::runner::TestEvaluation;
using testing::runner::WriteTestDataset;

int Get(const std::map<std::string, int>& m, const std::string& key) {
  auto it = m.find(key);
  return it == m.end() ? 0 : it->second;
}

// The data rows of a CSV text by their first field (no quoted fields in the test's tables).
std::map<std::string, std::string> RowsByName(const std::string& csv) {
  std::map<std::string, std::string> rows;
  std::istringstream lines(csv);
  std::string line;
  std::getline(lines, line);  // the header
  while (std::getline(lines, line)) {
    const size_t comma = line.find(',');
    rows[line.substr(0, comma)] = line.substr(comma);
  }
  return rows;
}

ShapeRecord RecordOf(const std::string& variant_dir, const std::string& name) {
  const std::string path = ShapeRecordPath(variant_dir, name);
  return ParseShapeRecord(name, ReadText(path), path);
}

// The three bent grids s0, s1, s2 of WriteTestDataset, with the mesh of s0 also under a0 and
// p0: a symlink and a byte copy with `distinct` false; else two regular files whose bytes differ
// from s0's (and each other's) by trailing newlines only, the same mesh. p0's ground truth is
// onto s0 (TestDataset), so it has no symmetric ground truth, a0 and s0 have.
std::string WriteAliasedDataset(const std::string& root, bool distinct) {
  const std::string config = WriteTestDataset(root, 3);
  const std::string s0 = root + "/shapes/s0.off";
  if (distinct) {
    WriteText(root + "/shapes/a0.off", ReadText(s0) + "\n");
    WriteText(root + "/shapes/p0.off", ReadText(s0) + "\n\n");
  } else {
    fs::create_symlink("s0.off", root + "/shapes/a0.off");
    fs::copy_file(s0, root + "/shapes/p0.off");
  }
  WriteText(root + "/pairs.txt", "s0 s1\ns1 s0\ns1 s2\ns2 s0\na0 s1\ns1 a0\na0 s2\np0 s0\n");
  return config;
}

const char* const kPairs[] = {"s0_s1", "s1_s0", "s1_s2", "s2_s0",
                              "a0_s1", "s1_a0", "a0_s2", "p0_s0"};

// s0, a0 (a symlink to it) and p0 (a byte copy) are one computation, without a cache and with
// an empty one: the per-shape stages run once per distinct mesh, the names after the first are
// recorded as cache hits with the first's times, and each name keeps its own record, its own
// shapes.csv row (p0's without the symmetric ground truth's measures) and its pairs. The maps,
// records and shapes.csv equal those of a run where a0 and p0 are distinct files, each computed.
TEST(ContentGroups, IdenticalMeshBytesUnderSeveralNamesAreComputedOnce) {
  TempDir tmp;
  const std::string distinct_config = WriteAliasedDataset(tmp.File("distinct"), true);
  const RunStats distinct = RunConfig(distinct_config, tmp.File("distinct_out"), "").stats;
  ASSERT_TRUE(distinct.ok());
  const std::string aliased_config = WriteAliasedDataset(tmp.File("aliased"), false);
  for (const std::string& cache : {std::string(""), tmp.File("cache")}) {
    SCOPED_TRACE("cache '" + cache + "'");
    const std::string out = tmp.File(cache.empty() ? "out_uncached" : "out_cached");
    const RunStats run = RunConfig(aliased_config, out, cache).stats;
    ASSERT_TRUE(run.ok());
    EXPECT_EQ(run.pairs_done, 8);
    EXPECT_EQ(run.shapes_computed, 5);
    EXPECT_EQ(run.shapes_shared, 2);
    for (const char* stage : {"preprocess", "sampling", "geodesics", "embedding", "symmetry",
                              "symmetrize", "test_feature"}) {
      EXPECT_EQ(Get(run.executed, stage), 3) << stage;  // s0's mesh, s1, s2
      EXPECT_EQ(Get(run.cache_hits, stage), 0) << stage;
    }

    // One of the three names computed (the first in name order), the others took its outcome.
    const std::string variant = out + "/base";
    const ShapeRecord computed = RecordOf(variant, "a0");
    for (const StageTime& time : computed.times) EXPECT_FALSE(time.cached) << time.stage;
    for (const char* name : {"p0", "s0"}) {
      const ShapeRecord reused = RecordOf(variant, name);
      ASSERT_EQ(reused.times.size(), computed.times.size()) << name;
      for (size_t i = 0; i < reused.times.size(); ++i) {
        EXPECT_EQ(reused.times[i].stage, computed.times[i].stage) << name;
        EXPECT_EQ(reused.times[i].seconds, computed.times[i].seconds) << name;
        EXPECT_TRUE(reused.times[i].cached) << name << " " << reused.times[i].stage;
      }
    }

    const std::map<std::string, std::string> rows = RowsByName(ReadText(variant + "/shapes.csv"));
    ASSERT_EQ(rows.size(), 5u);
    EXPECT_EQ(rows.at("a0"), rows.at("s0"));
    EXPECT_NE(rows.at("p0"), rows.at("s0"));  // no symmetric ground truth, no measures of it
    EXPECT_EQ(ReadText(variant + "/shapes.csv"),
              ReadText(tmp.File("distinct_out/base/shapes.csv")));
    for (const char* stem : kPairs) {
      const std::string map = "/maps/" + std::string(stem) + ".map";
      EXPECT_EQ(ReadText(variant + map), ReadText(tmp.File("distinct_out/base") + map)) << stem;
      const std::string record = "/pairs/" + std::string(stem) + ".rec";
      EXPECT_EQ(TestEvaluation::RecordBody(ReadText(variant + record)),
                TestEvaluation::RecordBody(ReadText(tmp.File("distinct_out/base") + record)))
          << stem;
    }
  }
}

// Names whose files differ in their bytes are computed separately, even when they hold the same
// mesh: the key is the content, not the parsed surface.
TEST(ContentGroups, NamesWithDifferentBytesAreComputedSeparately) {
  TempDir tmp;
  const RunStats run =
      RunConfig(WriteAliasedDataset(tmp.File("data"), true), tmp.File("out"), "").stats;
  ASSERT_TRUE(run.ok());
  EXPECT_EQ(run.shapes_computed, 5);
  EXPECT_EQ(run.shapes_shared, 0);
  EXPECT_EQ(Get(run.executed, "preprocess"), 5);
  for (const char* name : {"a0", "p0", "s0", "s1", "s2"}) {
    for (const StageTime& time : RecordOf(tmp.File("out/base"), name).times) {
      EXPECT_FALSE(time.cached) << name << " " << time.stage;
    }
  }
}

// A failure of the shared computation is every name's, each naming its own file; so is a
// warning of the shared computation.
TEST(ContentGroups, FailuresAndWarningsOfTheSharedComputationNameEachFile) {
  TempDir tmp;
  std::string config = WriteTestDataset(tmp.File("data"), 2);
  WriteText(tmp.File("data/shapes/x0.off"), "OFF\n3 1 0\n0 0 0\n");  // truncated
  fs::create_symlink("x0.off", tmp.File("data/shapes/y0.off"));
  fs::create_symlink("s0.off", tmp.File("data/shapes/a0.off"));
  WriteText(tmp.File("data/pairs.txt"), "x0 s0\ny0 s1\na0 s1\ns0 s1\n");
  const std::string from = "symmetry: {type: test}";
  config.replace(config.find(from), from.size(),
                 "symmetry: {type: test, second: true, second_fails: true}");
  const RunStats run = RunConfig(config, tmp.File("out"), "").stats;
  EXPECT_EQ(run.pairs_done, 2);
  std::set<std::string> failures;
  for (const Failure& f : run.failures) {
    if (f.kind == "shape") failures.insert(f.source + ": " + f.message);
  }
  EXPECT_EQ(failures, (std::set<std::string>{
                          "x0: " + tmp.File("data/shapes/x0.off") + ": truncated OFF mesh",
                          "y0: " + tmp.File("data/shapes/y0.off") + ": truncated OFF mesh"}));
  std::set<std::string> warned;
  for (const std::string& warning : run.warnings) {
    EXPECT_NE(warning.find("second plane hypothesis dropped"), std::string::npos) << warning;
    warned.insert(warning.substr(0, warning.find(": ")));
  }
  EXPECT_EQ(warned,
            (std::set<std::string>{tmp.File("data/shapes/a0.off"), tmp.File("data/shapes/s0.off"),
                                   tmp.File("data/shapes/s1.off")}));
}

// Shapes-only shards: a mesh under several names is computed by the shard of its first name
// only, and each other name is reported as computed with it.
TEST(ContentGroups, ShapesOnlyShardsComputeAMeshUnderSeveralNamesOnce) {
  TempDir tmp;
  const std::string config = WriteAliasedDataset(tmp.File("data"), false);
  std::map<std::string, std::string> reported;  // shape -> "computed" or the shape it went with
  int preprocessed = 0;
  for (int i = 0; i < 2; ++i) {
    RunOptions shapes;
    shapes.shapes_only = true;
    shapes.shard_index = i;
    shapes.shard_count = 2;
    shapes.on_shape = [&](const std::string& shape, const std::string&,
                          const std::vector<std::string>& computed,
                          const std::string& computed_with) {
      EXPECT_EQ(reported.count(shape), 0u) << shape;
      reported[shape] = computed_with.empty() ? "computed" : computed_with;
      EXPECT_EQ(computed.empty(), !computed_with.empty()) << shape;
    };
    const RunStats run = RunConfig(config, tmp.File("none"), tmp.File("cache"), shapes).stats;
    EXPECT_TRUE(run.ok());
    preprocessed += Get(run.executed, "preprocess");
  }
  EXPECT_EQ(preprocessed, 3);
  EXPECT_EQ(
      reported,
      (std::map<std::string, std::string>{
          {"a0", "computed"}, {"p0", "a0"}, {"s0", "a0"}, {"s1", "computed"}, {"s2", "computed"}}));
}

}  // namespace
}  // namespace symembed

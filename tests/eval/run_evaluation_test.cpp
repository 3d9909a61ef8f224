// The runner with the real evaluator behind it (eval/run_evaluation.h): the outputs of a run,
// of shards merged and of a resumed run are the same, timings aside.
#include "eval/run_evaluation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/errors.h"
#include "eval/report.h"
#include "registry/config.h"
#include "registry/merge.h"
#include "tests/eval/run_outputs_fixture.h"
#include "tests/registry/runner_fixture.h"

namespace symembed {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;
using testing::TempDir;
using testing::runner::ReadOff;
using testing::runner::TestRegistry;
using testing::runner::WriteTestDataset;

RunStats RunConfig(const std::string& config_text, const std::string& out, const std::string& cache,
                   RunOptions options = {}) {
  const Registry registry = TestRegistry();
  const ExperimentConfig config = ParseExperimentConfig(config_text, "test.yaml", registry);
  options.out_dir = out;
  options.cache_dir = cache;
  options.quiet = true;
  options.jobs = 2;
  options.load_mesh = ReadOff;
  GroundTruthRunEvaluation evaluation(&registry);
  return RunExperiment(config, registry, options, evaluation);
}

std::map<std::string, std::string> Outputs(const std::string& dir) {
  return testing::OutputsWithoutTimings(dir);
}

TEST(RunEvaluation, WritesTheEvaluatorsOutputs) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  const RunStats stats = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  EXPECT_TRUE(stats.ok());
  for (const char* file :
       {"summary.json", "pairs.csv", "curve.csv", "timings.csv", "failures.csv", "config.yaml"}) {
    EXPECT_TRUE(fs::exists(tmp.File("out/base/") + file)) << file;
  }
  EXPECT_TRUE(fs::exists(tmp.File("out/comparison.csv")));
  const VariantSummary summary = ReadSummaryJson(tmp.File("out/base/summary.json"));
  EXPECT_EQ(summary.pairs, 6);
  EXPECT_EQ(summary.failed_pairs, 0);
  // Same connectivity, identity matching: every ground-truth point maps exactly.
  EXPECT_EQ(summary.mean_direct, 0.0);
  EXPECT_EQ(summary.FlippedTotal(), 0);
}

TEST(RunEvaluation, VariantsWithTheSameEvaluationShareItsDistances) {
  TempDir tmp;
  const std::string variants = "variants:\n  - {name: flip2, set: {pipeline.flip.choose: 2}}\n";
  const std::string config = WriteTestDataset(tmp.File("data"), 3, variants);
  RunOptions base_only;
  base_only.variant = "base";
  testing::runner::CallCounter::Get().Take();
  RunConfig(config, tmp.File("one"), tmp.File("cache1"), base_only);
  const int one = testing::runner::CallCounter::Get().Take()["geodesics"];
  RunConfig(config, tmp.File("two"), tmp.File("cache2"));
  const int two = testing::runner::CallCounter::Get().Take()["geodesics"];
  // The test geodesics solver serves both the pipeline and the evaluation; flip2 reuses base's
  // per-shape chain (cache) and base's evaluation distances (shared Evaluator).
  EXPECT_GT(one, 3);
  EXPECT_EQ(two, one);
}

// A variant may load other meshes under the same names (a remeshed dataset): its errors are
// measured on its own meshes, exactly as when it runs alone, not on distances another variant
// left under the name.
TEST(RunEvaluation, AVariantWithOtherMeshesUnderTheSameNamesIsEvaluatedOnItsOwn) {
  TempDir tmp;
  WriteTestDataset(tmp.File("other"), 3);
  for (int k = 0; k < 3; ++k) {  // finer grids, bent the other way
    Surface s = GridMesh(7, 5);
    for (int i = 0; i < s.NumVertices(); ++i) s.V(i, 2) = -0.3 * (k + 1) * s.V(i, 1) * s.V(i, 1);
    testing::WriteText(tmp.File("other/shapes/s" + std::to_string(k) + ".off"),
                       testing::runner::OffText(s));
  }
  const std::string variants =
      "variants:\n  - {name: other, set: {dataset.root: " + tmp.File("other") +
      ", pipeline.flip.choose: 2}}\n";
  const std::string config = WriteTestDataset(tmp.File("data"), 3, variants);
  RunOptions alone;
  alone.variant = "other";
  EXPECT_TRUE(RunConfig(config, tmp.File("alone"), tmp.File("cache1"), alone).ok());
  EXPECT_TRUE(RunConfig(config, tmp.File("both"), tmp.File("cache2")).ok());
  const std::map<std::string, std::string> one = Outputs(tmp.File("alone/other"));
  const std::map<std::string, std::string> two = Outputs(tmp.File("both/other"));
  ASSERT_TRUE(one.count("pairs.csv"));
  EXPECT_EQ(one.at("pairs.csv"), two.at("pairs.csv"));
  EXPECT_EQ(one.at("summary.json"), two.at("summary.json"));
  // The choice of candidate 2 maps each grid onto its mirror image: the errors are not 0, so
  // the comparison above compares distances.
  EXPECT_GT(ReadSummaryJson(tmp.File("both/other/summary.json")).mean_direct, 0.0);
}

TEST(RunEvaluation, ReportsWhenRefinementMovesAMapOntoTheMirroredSolution) {
  TempDir tmp;
  const std::string variants =
      "variants:\n  - {name: mirrored, set: {pipeline.refine.mirror: true}}\n";
  const std::string config = WriteTestDataset(tmp.File("data"), 3, variants);
  RunConfig(config, tmp.File("out"), tmp.File("cache"));
  // The identity refinement leaves the map alone: nothing to report.
  const VariantSummary base = ReadSummaryJson(tmp.File("out/base/summary.json"));
  EXPECT_EQ(base.refine_to_symmetric, 0);
  EXPECT_EQ(base.refine_to_direct, 0);
  // The mirroring refinement takes every exact map onto the symmetric ground truth.
  const VariantSummary mirrored = ReadSummaryJson(tmp.File("out/mirrored/summary.json"));
  EXPECT_EQ(mirrored.refine_to_symmetric, 6);
  EXPECT_EQ(mirrored.refine_to_direct, 0);
  EXPECT_EQ(mirrored.flipped_left_right, 6);
  const std::string csv = ReadText(tmp.File("out/mirrored/pairs.csv"));
  EXPECT_NE(csv.find("initial_mean_direct,refine_side"), std::string::npos);
  EXPECT_NE(csv.find(",0,to_symmetric,"), std::string::npos) << csv;
  EXPECT_EQ(ReadText(tmp.File("out/base/pairs.csv")).find("to_symmetric"), std::string::npos);
}

TEST(RunEvaluation, PairRecordsKeepTheStageMessagesAndTheCandidatesErrors) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  RunConfig(config, tmp.File("out"), tmp.File("cache"));
  const std::string csv = ReadText(tmp.File("out/base/pairs.csv"));
  EXPECT_NE(csv.find(",candidate_errors,flip_message,refine_message,message\n"), std::string::npos)
      << csv;
  EXPECT_NE(csv.find(",test flip chose 0,"), std::string::npos) << csv;
  const PairEvaluation record = ParsePairRecord(ReadText(tmp.File("out/base/pairs/s0_s1.rec")));
  EXPECT_EQ(record.stage_messages.at("flip"), "test flip chose 0");
  // The oracle's four candidate errors: the identity (the bent grid's truth) is the lowest.
  ASSERT_EQ(record.candidate_errors.size(), 4u);
  EXPECT_EQ(*std::min_element(record.candidate_errors.begin(), record.candidate_errors.end()),
            record.candidate_errors[0]);
  EXPECT_EQ(record.oracle, 0);
}

TEST(RunEvaluation, RejectsAMalformedDistanceCacheBudget) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 2);
  setenv("SYMEMBED_EVAL_CACHE_MB", "lots", 1);
  EXPECT_THROW(RunConfig(config, tmp.File("bad"), tmp.File("cache")), ConfigError);
  setenv("SYMEMBED_EVAL_CACHE_MB", "0.001", 1);  // a tiny budget changes no result
  const RunStats tiny = RunConfig(config, tmp.File("tiny"), tmp.File("cache_tiny"));
  unsetenv("SYMEMBED_EVAL_CACHE_MB");
  const RunStats normal = RunConfig(config, tmp.File("normal"), tmp.File("cache_normal"));
  EXPECT_TRUE(tiny.ok());
  EXPECT_TRUE(normal.ok());
  EXPECT_EQ(Outputs(tmp.File("tiny")), Outputs(tmp.File("normal")));
}

TEST(RunEvaluation, ShardsMergedAndResumedRunsEqualASingleRun) {
  TempDir tmp;
  const std::string config = WriteTestDataset(
      tmp.File("data"), 4, "variants:\n  - {name: flip2, set: {pipeline.flip.choose: 2}}\n");
  // A bad mesh: its pairs fail in every form of the run alike.
  testing::WriteText(tmp.File("data/shapes/s3.off"), "OFF\n");
  EXPECT_FALSE(RunConfig(config, tmp.File("single"), tmp.File("cache")).ok());
  const auto single = Outputs(tmp.File("single"));
  EXPECT_NE(single.at("flip2/pairs.csv").find("front_back"), std::string::npos)
      << single.at("flip2/pairs.csv");

  std::vector<std::string> shards;
  for (int i = 0; i < 3; ++i) {
    RunOptions shard;
    shard.shard_index = i;
    shard.shard_count = 3;
    shards.push_back(tmp.File("shard" + std::to_string(i)));
    RunConfig(config, shards.back(), tmp.File("cache"), shard);
  }
  GroundTruthRunEvaluation evaluation;
  EXPECT_EQ(MergeRuns(shards, tmp.File("merged"), evaluation).size(), 2u * (1 + 6));
  EXPECT_EQ(Outputs(tmp.File("merged")), single);

  RunConfig(config, tmp.File("resumed"), tmp.File("cache"));
  for (const char* stem : {"s0_s1", "s2_s1"})
    fs::remove(tmp.File("resumed/base/pairs/") + stem + ".rec");
  fs::remove(tmp.File("resumed/base/summary.json"));
  RunOptions resume;
  resume.resume = true;
  const RunStats stats = RunConfig(config, tmp.File("resumed"), tmp.File("cache"), resume);
  EXPECT_EQ(stats.pairs_done, 2);
  EXPECT_EQ(Outputs(tmp.File("resumed")), single);
}

}  // namespace
}  // namespace symembed

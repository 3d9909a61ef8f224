// The runner with the real evaluator behind it (harness/run_evaluation.h): the outputs of a run,
// of shards merged and of a resumed run are the same, timings aside.
#include "harness/run_evaluation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <tuple>

#include "core/errors.h"
#include "core/map_io.h"
#include "core/primitives.h"
#include "eval/report.h"
#include "eval/score_maps.h"
#include "harness/config.h"
#include "harness/html/html_report.h"
#include "harness/html/report_data.h"
#include "harness/merge.h"
#include "tests/eval/euclidean_geodesics.h"
#include "tests/harness/run_outputs_fixture.h"
#include "tests/harness/runner_fixture.h"

namespace symembed {
namespace {

namespace fs = std::filesystem;
using testing::ReadText;
using testing::TempDir;
using testing::runner::OffText;
using testing::runner::ReadOff;
using testing::runner::RunShards;
using testing::runner::TestRegistry;
using testing::runner::WriteTestDataset;

// Two jobs unless `options` names another number.
RunStats RunConfig(const std::string& config_text, const std::string& out, const std::string& cache,
                   RunOptions options = {}) {
  const Registry registry = TestRegistry();
  const ExperimentConfig config = ParseExperimentConfig(config_text, "test.yaml", registry);
  options.out_dir = out;
  options.cache_dir = cache;
  options.quiet = true;
  if (options.jobs == 0) options.jobs = 2;
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

// With room for one target's distance rows, the second variant starts with the target the first
// ended with, whose rows it finds in the cache; in the first variant's order it would find that
// target evicted by the two before it.
TEST(RunEvaluation, TheNextVariantStartsWithTheTargetTheCacheStillHolds) {
  TempDir tmp;
  const std::string config = WriteTestDataset(
      tmp.File("data"), 3, "variants:\n  - {name: flip2, set: {pipeline.flip.choose: 2}}\n");
  RunOptions one_job;
  one_job.jobs = 1;
  // 20 float rows of 20 vertices per target: 1,600 bytes; two do not fit.
  setenv("SYMEMBED_EVAL_CACHE_MB", "0.002", 1);
  const RunStats stats = RunConfig(config, tmp.File("out"), tmp.File("cache"), one_job);
  unsetenv("SYMEMBED_EVAL_CACHE_MB");
  ASSERT_TRUE(stats.ok());
  auto distance_seconds = [&](const std::string& variant, const std::string& stem) {
    const PairEvaluation record =
        ParsePairRecord(ReadText(tmp.File("out/" + variant + "/pairs/" + stem + ".rec")));
    return record.stage_seconds.at("ground_truth_distances");
  };
  // The first variant computes the rows of every target (targets in ascending order, s2 last);
  // the second, every pair onto s2 first, finds them all.
  EXPECT_GT(distance_seconds("base", "s0_s2") + distance_seconds("base", "s1_s2"), 0.0);
  EXPECT_EQ(distance_seconds("flip2", "s0_s2"), 0.0);
  EXPECT_EQ(distance_seconds("flip2", "s1_s2"), 0.0);
  // Its other targets' rows were evicted: computed again.
  EXPECT_GT(distance_seconds("flip2", "s1_s0") + distance_seconds("flip2", "s2_s0"), 0.0);
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

  const std::vector<std::string> shards =
      RunShards(tmp, 3, [&](const std::string& out, const RunOptions& shard) {
        RunConfig(config, out, tmp.File("cache"), shard);
      });
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

// Shapes a, a_b1, c1, b1_c1 (the p, p_q1, r1, q1_r1; names starting with 'p' have ground
// truth onto s0 in the test dataset) with the pairs a_b1 -> c1 and a -> b1_c1, whose plain stems
// are both "a_b1_c1". The sources differ in size (a_b1: 12 vertices, a: 20), so a pair read with
// the other's map fails instead of passing unnoticed. Returns the config text.
std::string WriteCollidingDataset(const std::string& root) {
  const std::string config = WriteTestDataset(root, 0);
  for (const auto& [name, nx, ny] : {std::tuple{"a", 5, 4}, std::tuple{"a_b1", 4, 3},
                                     std::tuple{"c1", 5, 4}, std::tuple{"b1_c1", 5, 4}}) {
    Surface s = GridMesh(nx, ny);
    for (int i = 0; i < s.NumVertices(); ++i) s.V(i, 2) = 0.2 * s.V(i, 0) * s.V(i, 0);
    testing::WriteText(root + "/shapes/" + name + ".off", OffText(s));
  }
  testing::WriteText(root + "/pairs.txt", "a_b1 c1\na b1_c1\n");
  return config;
}

// The files of a folder, sorted by name.
std::vector<std::string> FileNames(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(RunEvaluation, PairsWhosePlainFileNamesCollideKeepTheirOwnMapsAndRecords) {
  TempDir tmp;
  const std::string config = WriteCollidingDataset(tmp.File("data"));
  ASSERT_TRUE(RunConfig(config, tmp.File("single"), tmp.File("cache")).ok());
  const std::string variant = tmp.File("single/base");
  ASSERT_EQ(FileNames(variant + "/maps").size(), 2u);
  ASSERT_EQ(FileNames(variant + "/pairs").size(), 2u);
  // Each record holds its own pair, and each map one id per vertex of that pair's source.
  std::map<std::string, std::string> record_of;  // "source target" -> record file
  for (const std::string& file : FileNames(variant + "/pairs")) {
    const PairEvaluation record = ParsePairRecord(ReadText(variant + "/pairs/" + file), file);
    EXPECT_TRUE(record.ok) << file;
    record_of[record.source + " " + record.target] = file;
  }
  ASSERT_EQ(record_of.size(), 2u);
  ASSERT_TRUE(record_of.count("a_b1 c1") && record_of.count("a b1_c1"));
  const std::map<std::string, size_t> source_vertices = {{"a_b1 c1", 12}, {"a b1_c1", 20}};
  for (const auto& [pair, file] : record_of) {
    const std::string stem = fs::path(file).stem().string();
    EXPECT_EQ(ReadMapFile(variant + "/maps/" + stem + ".map", 1, -1, -1).size(),
              source_vertices.at(pair))
        << stem;
  }

  // --resume proves both pairs and computes neither again.
  RunOptions resume;
  resume.resume = true;
  const RunStats resumed = RunConfig(config, tmp.File("single"), tmp.File("cache"), resume);
  EXPECT_EQ(resumed.pairs_skipped, 2);
  EXPECT_EQ(resumed.pairs_recomputed, 0);
  EXPECT_EQ(resumed.pairs_done, 0);
  EXPECT_TRUE(resumed.warnings.empty()) << resumed.warnings[0];

  // One pair per shard, merged: the single run's outputs, both pairs scored.
  const std::vector<std::string> shards =
      RunShards(tmp, 2, [&](const std::string& out, const RunOptions& shard) {
        EXPECT_TRUE(RunConfig(config, out, tmp.File("cache"), shard).ok()) << out;
      });
  GroundTruthRunEvaluation evaluation;
  EXPECT_TRUE(MergeRuns(shards, tmp.File("merged"), evaluation).empty());
  EXPECT_EQ(Outputs(tmp.File("merged")), Outputs(tmp.File("single")));

  // `symembed eval` of the run's maps reads each pair's own map, and scores it as the run did.
  testing::runner::TestDataset dataset(tmp.File("data"));
  testing::runner::TestPreprocess preprocess;
  testing::EuclideanGeodesics geodesics;
  EvaluationOptions options;
  options.geodesics = "test";
  Evaluator evaluator(options, geodesics);
  ScoreMapsOptions maps;
  maps.maps_dir = variant + "/maps";
  const auto load = [](const DatasetShape& shape) { return ReadOff(shape.mesh_path); };
  const ScoreMapsResult scored = ScoreMaps(dataset, preprocess, evaluator, maps, load);
  ASSERT_EQ(scored.pairs.size(), 2u);
  for (const PairEvaluation& p : scored.pairs) {
    ASSERT_TRUE(p.ok) << p.source << " -> " << p.target << ": " << p.message;
    const std::string file = record_of.at(p.source + " " + p.target);
    const PairEvaluation run = ParsePairRecord(ReadText(variant + "/pairs/" + file), file);
    EXPECT_EQ(p.points, run.points);
    EXPECT_NEAR(p.mean_direct, run.mean_direct, 1e-6);  // the same evaluator; float distances
  }
}

// timings.csv names each pair by its file stem, and the report reads each pair's stage times,
// map and record under it.
TEST(RunEvaluation, TimingsAndReportOfPairsWhosePlainFileNamesCollideAreTheirOwn) {
  TempDir tmp;
  const std::string config = WriteCollidingDataset(tmp.File("data"));
  ASSERT_TRUE(RunConfig(config, tmp.File("out"), tmp.File("cache")).ok());
  const std::string variant = tmp.File("out/base");
  const std::string timings = ReadText(variant + "/timings.csv");
  EXPECT_NE(timings.find("\npair,a%5Fb1_c1,"), std::string::npos) << timings;
  EXPECT_NE(timings.find("\npair,a_b1_c1,"), std::string::npos) << timings;

  HtmlReportOptions report;
  report.threads = 2;
  const HtmlReportResult html = WriteHtmlReport(tmp.File("out"), report, TestRegistry());
  EXPECT_EQ(html.pairs_viewable, 2);
  EXPECT_EQ(html.pairs_unavailable, 0) << html.warnings[0];
  const JsonValue data = VariantReportData({"base", variant});
  ASSERT_EQ(data.Get("pairs").items().size(), 2u);
  for (const JsonValue& row : data.Get("pairs").items()) {
    const std::string source = row.Get("source").AsString(), target = row.Get("target").AsString();
    const std::string stem = source == "a" ? "a_b1_c1" : "a%5Fb1_c1";
    const PairEvaluation record = ParsePairRecord(ReadText(variant + "/pairs/" + stem + ".rec"));
    ASSERT_EQ(record.source, source);
    ASSERT_FALSE(record.stage_seconds.empty());
    for (const auto& [stage, seconds] : record.stage_seconds) {
      // timings.csv keeps 8 significant digits.
      EXPECT_NEAR(row.Get("seconds").Get(stage).AsNumber(), seconds, 1e-7 * seconds)
          << source << " -> " << target << ": " << stage;
    }
  }
}

}  // namespace
}  // namespace symembed

#include "eval/score_maps.h"

#include <gtest/gtest.h>

#include <map>

#include "core/map_io.h"
#include "core/primitives.h"
#include "eval/report.h"
#include "tests/eval/euclidean_geodesics.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// 4 x 4 grids on [0, 3]^2 named a, b, c; ground truth: identity, mirrored in x.
constexpr int kN = 4;

class GridDataset : public Dataset {
 public:
  DatasetIndex Load() const override {
    DatasetIndex index;
    for (const char* name : {"a", "b", "c"}) index.shapes.push_back({name, "grid", name});
    index.pairs = {{"a", "b"}, {"a", "c"}, {"b", "c"}, {"a", "zzz"}};
    return index;
  }
  ShapeGroundTruth GroundTruth(const DatasetShape&, int num_vertices) const override {
    ShapeGroundTruth gt;
    for (int v = 0; v < num_vertices; ++v) {
      gt.ids.push_back(v);
      gt.sym_ids.push_back((v / kN) * kN + (kN - 1 - v % kN));
    }
    return gt;
  }
};

// Keeps every vertex and coordinate (so errors are hand-computable on the input grid).
class IdentityPreprocess : public PreprocessStage {
 public:
  PreprocessResult Run(const Surface& input) const override {
    PreprocessResult pre;
    pre.surface = input;
    for (int v = 0; v < input.NumVertices(); ++v) pre.input_ids.push_back(v);
    return pre;
  }
};

Surface LoadGrid(const DatasetShape&) { return GridMesh(kN, kN, 3.0, 3.0); }

// Scores the grid maps in maps_dir (options: the rest of ScoreMapsOptions) on the dataset's
// pairs with exact (Euclidean) distances on the unchanged grids.
ScoreMapsResult ScoreGrids(const Dataset& dataset, const std::string& maps_dir,
                           ScoreMapsOptions options = {}) {
  IdentityPreprocess preprocess;
  testing::EuclideanGeodesics geodesics;
  Evaluator evaluator(EvaluationOptions{}, geodesics);
  options.maps_dir = maps_dir;
  return ScoreMaps(dataset, preprocess, evaluator, options, LoadGrid);
}

std::vector<int> Identity() {
  std::vector<int> map(kN * kN);
  for (int v = 0; v < kN * kN; ++v) map[v] = v;
  return map;
}

TEST(ScoreMaps, MalformedAndMissingMapsFailOnlyTheirPair) {
  testing::TempDir dir;
  WriteMapFile(dir.File("a_b.map"), Identity());
  std::string bad = FormatMap(Identity());
  bad.replace(bad.find("3\n"), 2, "NaN\n");  // line 3
  testing::WriteText(dir.File("a_c.map"), bad);
  // b_c.map is missing.
  GridDataset dataset;
  ScoreMapsOptions options;
  options.threads = 2;
  const ScoreMapsResult r = ScoreGrids(dataset, dir.path(), options);
  ASSERT_EQ(r.pairs.size(), 4u);
  EXPECT_EQ(r.pairs[0].target, "b");
  EXPECT_TRUE(r.pairs[0].ok) << r.pairs[0].message;
  EXPECT_NEAR(r.pairs[0].mean_direct, 0.0, 1e-9);  // exact distances, zero error
  EXPECT_EQ(r.pairs[0].flip, FlipClass::kNone);
  EXPECT_FALSE(r.pairs[1].ok);
  EXPECT_NE(r.pairs[1].message.find("a_c.map:3: NaN"), std::string::npos) << r.pairs[1].message;
  EXPECT_EQ(r.pairs[2].target, "zzz");
  EXPECT_NE(r.pairs[2].message.find("zzz is not in the dataset"), std::string::npos);
  EXPECT_FALSE(r.pairs[3].ok);
  EXPECT_NE(r.pairs[3].message.find("b_c.map"), std::string::npos) << r.pairs[3].message;
  EXPECT_EQ(r.timings.shape_stage_seconds.size(), 3u);

  // The outputs record the failures.
  const VariantSummary s = Summarize("ext", r.pairs, EvaluationOptions{}, r.timings);
  EXPECT_EQ(s.pairs, 4);
  EXPECT_EQ(s.failed_pairs, 3);
  WriteVariantOutputs(dir.File("out"), s, r.pairs, r.timings);
  const std::string csv = testing::ReadText(dir.File("out/pairs.csv"));
  EXPECT_NE(csv.find("a,c,failed"), std::string::npos) << csv;
  EXPECT_NE(csv.find("NaN entry"), std::string::npos) << csv;
}

TEST(ScoreMaps, ReverseScoresTheFileAsTheOppositePair) {
  testing::TempDir dir;
  // a_b.map maps b to a, mirrored: with --reverse it is the pair b -> a, a left-right flip.
  std::vector<int> mirror(kN * kN);
  for (int v = 0; v < kN * kN; ++v) mirror[v] = (v / kN) * kN + (kN - 1 - v % kN);
  WriteMapFile(dir.File("a_b.map"), mirror);
  GridDataset dataset;
  ScoreMapsOptions options;
  options.reverse = true;
  const ScoreMapsResult r = ScoreGrids(dataset, dir.path(), options);
  const PairEvaluation* ba = nullptr;
  for (const auto& p : r.pairs) {
    if (p.source == "b" && p.target == "a") ba = &p;
  }
  ASSERT_NE(ba, nullptr);
  ASSERT_TRUE(ba->ok) << ba->message;
  EXPECT_EQ(ba->flip, FlipClass::kLeftRight);
  EXPECT_NEAR(ba->mean_flip_tolerant, 0.0, 1e-9);
  // Mirror error |2x - 3| / 3 over x = 0..3: (3 + 1 + 1 + 3) / 4 / 3.
  EXPECT_NEAR(ba->mean_direct, 2.0 / 3.0, 1e-6);  // float cache
}

// "part" has ground truth onto "whole" only (as SHREC'16's partial shapes onto their null
// shape): its vertex v is the whole's vertex v + kN (the grid one row up).
class OntoDataset : public Dataset {
 public:
  DatasetIndex Load() const override {
    DatasetIndex index;
    for (const char* name : {"part", "whole"}) index.shapes.push_back({name, "grid", name});
    index.pairs = {{"part", "whole"}};
    return index;
  }
  ShapeGroundTruth GroundTruth(const DatasetShape& shape, int) const override {
    ShapeGroundTruth gt;
    if (shape.name != "part") return gt;
    gt.onto = "whole";
    for (int v = 0; v < kN * (kN - 1); ++v) {
      gt.onto_lines.source_ids.push_back(v);
      gt.onto_lines.target_ids.push_back(v + kN);
    }
    return gt;
  }
};

TEST(ScoreMaps, GroundTruthOntoAnotherShapeScoresThroughItsLines) {
  testing::TempDir dir;
  std::vector<int> up(kN * kN);
  for (int v = 0; v < kN * kN; ++v) up[v] = std::min(v + kN, kN * kN - 1);
  WriteMapFile(dir.File("part_whole.map"), Identity());
  OntoDataset dataset;
  ScoreMapsResult r = ScoreGrids(dataset, dir.path());
  ASSERT_EQ(r.pairs.size(), 1u);
  ASSERT_TRUE(r.pairs[0].ok) << r.pairs[0].message;
  EXPECT_EQ(r.pairs[0].points, kN * (kN - 1));
  EXPECT_NEAR(r.pairs[0].mean_direct, 1.0 / 3.0, 1e-6);  // one row off, over sqrt(area 9)
  WriteMapFile(dir.File("part_whole.map"), up);
  r = ScoreGrids(dataset, dir.path());
  ASSERT_TRUE(r.pairs[0].ok) << r.pairs[0].message;
  EXPECT_NEAR(r.pairs[0].mean_direct, 0.0, 1e-9);
}

// p_q1 -> r1 and p -> q1_r1 would both be p_q1_r1.map; a -> b keeps a_b.map.
class CollidingDataset : public GridDataset {
 public:
  DatasetIndex Load() const override {
    DatasetIndex index;
    for (const char* name : {"p", "p_q1", "r1", "q1_r1", "a", "b"}) {
      index.shapes.push_back({name, "grid", name});
    }
    index.pairs = {{"p_q1", "r1"}, {"p", "q1_r1"}, {"a", "b"}};
    return index;
  }
};

TEST(ScoreMaps, AnAmbiguousPlainNameIsNotReadAndTheEscapedOnesAreNamed) {
  testing::TempDir dir;
  // A peer's folder: one file for the two colliding pairs, a_b.map as always.
  WriteMapFile(dir.File("p_q1_r1.map"), Identity());
  WriteMapFile(dir.File("a_b.map"), Identity());
  CollidingDataset dataset;
  ScoreMapsOptions options;
  options.threads = 2;
  ScoreMapsResult r = ScoreGrids(dataset, dir.path(), options);
  std::map<std::string, const PairEvaluation*> by_source;
  for (const PairEvaluation& p : r.pairs) by_source[p.source] = &p;
  ASSERT_EQ(by_source.size(), 3u);
  EXPECT_TRUE(by_source.at("a")->ok) << by_source.at("a")->message;
  // p -> q1_r1's escaped name is the plain one; p_q1 -> r1 is read from its escaped name only.
  EXPECT_TRUE(by_source.at("p")->ok) << by_source.at("p")->message;
  EXPECT_FALSE(by_source.at("p_q1")->ok);
  EXPECT_NE(by_source.at("p_q1")->message.find(dir.File("p%5Fq1_r1.map") + ": cannot read"),
            std::string::npos)
      << by_source.at("p_q1")->message;
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_NE(r.warnings[0].find("p_q1_r1.map would be ambiguous"), std::string::npos)
      << r.warnings[0];
  EXPECT_NE(r.warnings[0].find("p_q1 -> r1 from p%5Fq1_r1.map"), std::string::npos)
      << r.warnings[0];

  WriteMapFile(dir.File("p%5Fq1_r1.map"), Identity());
  r = ScoreGrids(dataset, dir.path(), options);
  for (const PairEvaluation& p : r.pairs) EXPECT_TRUE(p.ok) << p.source << ": " << p.message;
}

}  // namespace
}  // namespace symembed

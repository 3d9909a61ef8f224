#include "harness/runner.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>

#include "core/procrustes.h"
#include "harness/config.h"
#include "harness/merge.h"
#include "harness/pair_pipeline.h"
#include "harness/shape_pipeline.h"
#include "tests/harness/runner_fixture.h"

namespace symembed {
namespace {

namespace fs = std::filesystem;

// The values of one column of a CSV text without quoted fields, one per data row.
std::vector<std::string> CsvColumn(const std::string& text, const std::string& name) {
  std::istringstream lines(text);
  std::string line;
  std::vector<std::string> values;
  int index = -1;
  while (std::getline(lines, line)) {
    std::vector<std::string> fields;
    std::istringstream row(line);
    for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
    if (index < 0) {
      for (size_t i = 0; i < fields.size(); ++i) {
        if (fields[i] == name) index = static_cast<int>(i);
      }
      if (index < 0) return values;
    } else {
      values.push_back(index < static_cast<int>(fields.size()) ? fields[index] : "");
    }
  }
  return values;
}

using testing::ReadText;
using testing::TempDir;
using testing::WriteText;
using testing::runner::CallCounter;
using testing::runner::ReadOff;
using testing::runner::RunConfig;
using testing::runner::RunResult;
using testing::runner::RunShards;
using testing::runner::TestEvaluation;
using testing::runner::TestRegistry;
using testing::runner::WriteTestDataset;

// Points mirrored across x = 0 in pairs (a_i, b_i), plus two points on the plane.
Eigen::MatrixX3d MirroredPairs(std::vector<int>* a, std::vector<int>* b) {
  Eigen::MatrixX3d Y(8, 3);
  Y << 1, 0, 0, -1, 0, 0, 2, 1, 0, -2, 1, 0, 0.5, -1, 1, -0.5, -1, 1, 0, 2, 0, 0, -2, 1;
  *a = {0, 2, 4, 6, 7};
  *b = {1, 3, 5, 6, 7};
  return Y;
}

TEST(SymmetryGroundTruthError, ZeroForTheTrueMirrorLargeForAnotherPlaneAndMinusOneWithoutLines) {
  std::vector<int> a, b;
  const Eigen::MatrixX3d Y = MirroredPairs(&a, &b);
  EXPECT_NEAR(SymmetryGroundTruthError(Y, a, b), 0.0, 1e-12);
  // The same points with the symmetry plane turned to z = 0 (x and z swapped): the partners
  // are no longer mirror images across x = 0.
  Eigen::MatrixX3d turned = Y;
  turned.col(0).swap(turned.col(2));
  EXPECT_GT(SymmetryGroundTruthError(turned, a, b), 0.5);
  // Lines without both ids are skipped; none left gives -1.
  EXPECT_NEAR(SymmetryGroundTruthError(Y, {0, -1}, {1, 3}), 0.0, 1e-12);
  EXPECT_EQ(SymmetryGroundTruthError(Y, {-1, 2}, {1, -1}), -1.0);
}

// A flat strip of (2m+1) x rows vertices, x = -m..m, triangulated so that its edge graph is
// mirror-symmetric across x = 0; (*mirror)[v] is the vertex at v's mirror position.
Surface MirroredStrip(int m, int rows, std::vector<int>* mirror) {
  const int cols = 2 * m + 1;
  auto id = [&](int c, int r) { return r * cols + (c + m); };
  Surface s;
  s.V.resize(cols * rows, 3);
  mirror->assign(cols * rows, -1);
  for (int r = 0; r < rows; ++r) {
    for (int c = -m; c <= m; ++c) {
      s.V.row(id(c, r)) << c, r, 0.0;
      (*mirror)[id(c, r)] = id(-c, r);
    }
  }
  std::vector<Eigen::Vector3i> faces;
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = -m; c < m; ++c) {
      if (c >= 0) {
        faces.emplace_back(id(c, r), id(c + 1, r), id(c + 1, r + 1));
        faces.emplace_back(id(c, r), id(c + 1, r + 1), id(c, r + 1));
      } else {
        faces.emplace_back(id(c, r), id(c + 1, r), id(c, r + 1));
        faces.emplace_back(id(c + 1, r), id(c + 1, r + 1), id(c, r + 1));
      }
    }
  }
  s.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) s.F.row(static_cast<int>(f)) = faces[f].transpose();
  return s;
}

// A surface whose edge graph is mirror-symmetric has symmetric distances; stretching one half
// (as a pose that stretches one side of a body) makes them asymmetric, more so the more it is
// stretched. Too few lines give -1.
TEST(GroundTruthGeodesicAsymmetry, ZeroForASymmetricSurfaceGrowingWithAOneSidedStretch) {
  std::vector<int> mirror;
  Surface strip = MirroredStrip(6, 9, &mirror);
  std::vector<int> ids(mirror.size());
  for (size_t v = 0; v < ids.size(); ++v) ids[v] = static_cast<int>(v);
  EXPECT_NEAR(GroundTruthGeodesicAsymmetry(strip, ids, mirror), 0.0, 1e-12);
  double previous = 0.0;
  for (double stretch : {1.2, 1.6}) {
    Surface stretched = strip;
    for (int v = 0; v < stretched.NumVertices(); ++v) {
      if (stretched.V(v, 0) > 0.0) stretched.V(v, 0) *= stretch;
    }
    const double asymmetry = GroundTruthGeodesicAsymmetry(stretched, ids, mirror);
    EXPECT_GT(asymmetry, previous + 0.01) << stretch;
    previous = asymmetry;
  }
  EXPECT_EQ(GroundTruthGeodesicAsymmetry(strip, {0, -1}, {5, 3}), -1.0);
  EXPECT_EQ(GroundTruthGeodesicAsymmetry(strip, ids, mirror, 1), -1.0);
}

// The self map of MirroredPairs' points (partners swapped, points on the plane fixed) moves
// them across the plane; the identity moves nothing; an invalid map gives -1.
TEST(SelfMapDisplacement, LargeForTheMirrorZeroForTheIdentity) {
  std::vector<int> a, b;
  ShapeData data;
  data.embedding.Y = MirroredPairs(&a, &b);
  data.samples = {0, 1, 2, 3, 4, 5, 6, 7};
  data.symmetry.sigma = {1, 0, 3, 2, 5, 4, 6, 7};
  const Eigen::MatrixXd& P = data.embedding.Y;
  const double size = RmsRadius(P);
  const double expected = (2 * 2.0 + 2 * 4.0 + 2 * 1.0) / 8 / size;
  EXPECT_NEAR(SelfMapDisplacement(data), expected, 1e-12);
  data.symmetry.sigma = data.samples;
  EXPECT_EQ(SelfMapDisplacement(data), 0.0);
  data.symmetry.sigma = {1, 0};
  EXPECT_EQ(SelfMapDisplacement(data), -1.0);
}

// A body pressed into its plane is thin along x; a round one is not.
TEST(CanonicalXSpread, SmallForABodyPressedIntoItsPlane) {
  std::vector<int> a, b;
  Eigen::MatrixX3d Y = MirroredPairs(&a, &b);
  const double spread = CanonicalXSpread(Y);
  EXPECT_GT(spread, 0.5);
  Y.col(0) *= 0.05;
  EXPECT_NEAR(CanonicalXSpread(Y), 0.05 * spread, 1e-12);
  EXPECT_EQ(CanonicalXSpread(Eigen::MatrixX3d::Zero(1, 3)), -1.0);
}

// Every file below dir (relative path -> bytes), without the shape records (they hold times)
// and without leftover temporary files.
std::map<std::string, std::string> Snapshot(const std::string& dir) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), dir).string();
    if (rel.find("/shapes/") != std::string::npos || rel.find(".tmp.") != std::string::npos) {
      continue;
    }
    files[rel] = ReadText(e.path().string());
  }
  return files;
}

int Get(const std::map<std::string, int>& m, const std::string& key) {
  auto it = m.find(key);
  return it == m.end() ? 0 : it->second;
}

TEST(Runner, WritesMapsRecordsAndSummaries) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  EXPECT_TRUE(run.stats.ok());
  EXPECT_EQ(run.stats.pairs_total, 6);
  EXPECT_EQ(run.stats.pairs_done, 6);
  const std::string variant = tmp.File("out/base");
  EXPECT_TRUE(fs::exists(variant + "/config.yaml"));
  EXPECT_EQ(ReadText(variant + "/failures.csv"), "kind,source,target,message\n");
  // Identical connectivity and identity matching: the map is the identity, 1-based.
  const std::string map = ReadText(variant + "/maps/s0_s1.map");
  EXPECT_EQ(map.substr(0, 6), "1\n2\n3\n");
  EXPECT_EQ(std::count(map.begin(), map.end(), '\n'), 20);
  // The oracle of a bent grid is the identity rotation.
  EXPECT_EQ(TestEvaluation::RecordBody(ReadText(variant + "/pairs/s0_s1.rec")).substr(0, 10),
            "s0 s1 0 0 ");
  EXPECT_EQ(ReadText(tmp.File("out/comparison.txt")), "base\n");
  EXPECT_EQ(ReadText(tmp.File("out/variants.txt")), "base\n");
}

// A shape's ground truth given onto another shape (SHREC'16 partial shapes, TOPKIDS) reaches
// its pair: p0's vertex i is s0's mirror of i, so the identity map is off by the mirror.
TEST(Runner, GroundTruthOntoAnotherShapeReachesItsPair) {
  TempDir tmp;
  std::string config = WriteTestDataset(tmp.File("data"), 1);
  fs::copy_file(tmp.File("data/shapes/s0.off"), tmp.File("data/shapes/p0.off"));
  WriteText(tmp.File("data/pairs.txt"), "p0 s0\n");
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  ASSERT_TRUE(run.stats.ok());
  ASSERT_EQ(run.stats.pairs_done, 1);
  std::istringstream record(
      TestEvaluation::RecordBody(ReadText(tmp.File("out/base/pairs/p0_s0.rec"))));
  std::string source, target;
  int chosen = 0, oracle = 0;
  double mean = -1;
  record >> source >> target >> chosen >> oracle >> mean;
  const Surface grid = GridMesh(5, 4);
  double expected = 0;
  for (int i = 0; i < grid.NumVertices(); ++i) {
    expected += (grid.V.row(i) - grid.V.row(testing::runner::GridMirror(i))).norm() / grid.NumVertices();
  }
  EXPECT_GT(expected, 0.1);
  EXPECT_NEAR(mean, expected, 1e-12);
}

// --write-embeddings: each shape's canonical embedding on its faces, loadable as a mesh; none
// without it.
TEST(Runner, WritesTheCanonicalEmbeddingsWhenAsked) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  EXPECT_TRUE(RunConfig(config, tmp.File("plain"), tmp.File("cache")).stats.ok());
  EXPECT_FALSE(fs::exists(tmp.File("plain/base/embeddings")));
  RunOptions options;
  options.write_embeddings = true;
  EXPECT_TRUE(RunConfig(config, tmp.File("out"), tmp.File("cache"), options).stats.ok());
  for (const char* name : {"s0", "s1", "s2"}) {
    const std::string path = tmp.File("out/base/embeddings/") + name + ".off";
    ASSERT_TRUE(fs::exists(path)) << path;
    const Surface embedded = ReadOff(path);
    const Surface input = ReadOff(tmp.File("data/shapes/") + name + ".off");
    EXPECT_EQ(embedded.NumVertices(), input.NumVertices()) << name;
    EXPECT_EQ(embedded.F, input.F) << name;
    EXPECT_TRUE(embedded.V.allFinite()) << name;
  }
}

// A symmetry stage with a second plane hypothesis: each shape is kept under both planes, the
// flip stage scores every combination of a pair's planes, and the pair goes on with the lowest
// (here the source's second plane, whose embedding is mirrored in x, with the target's first:
// the map becomes the grid's mirror); shapes.csv says which shapes have one.
TEST(Runner, APairTakesTheCombinationOfPlanesItsFlipStageScoresLowest) {
  TempDir tmp;
  std::string config = WriteTestDataset(tmp.File("data"), 3);
  const RunResult plain = RunConfig(config, tmp.File("plain"), tmp.File("cache"));
  ASSERT_TRUE(plain.stats.ok());
  EXPECT_EQ(Get(plain.calls, "flip"), 6);
  EXPECT_EQ(Get(plain.calls, "symmetry_second"), 0);
  const std::string from = "symmetry: {type: test}";
  config.replace(config.find(from), from.size(), "symmetry: {type: test, second: true}");
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  ASSERT_TRUE(run.stats.ok());
  EXPECT_EQ(Get(run.calls, "symmetry_second"), 3);
  EXPECT_EQ(Get(run.calls, "flip"), 6 * 4);
  const std::string identity = ReadText(tmp.File("plain/base/maps/s0_s1.map"));
  EXPECT_EQ(identity.substr(0, 6), "1\n2\n3\n");
  EXPECT_NE(ReadText(tmp.File("out/base/maps/s0_s1.map")), identity);
  const std::string record =
      TestEvaluation::RecordBody(ReadText(tmp.File("out/base/pairs/s0_s1.rec")));
  EXPECT_NE(record.find("planes (source/target): first/first 1, first/second 1.25, second/first "
                        "0.5, second/second 0.75; chosen second/first"),
            std::string::npos)
      << record;
  const std::vector<std::string> all = {"1", "1", "1"}, none = {"0", "0", "0"};
  EXPECT_EQ(CsvColumn(ReadText(tmp.File("out/base/shapes.csv")), "second_plane"), all);
  EXPECT_EQ(CsvColumn(ReadText(tmp.File("plain/base/shapes.csv")), "second_plane"), none);
}

// A second plane hypothesis whose symmetrization fails is dropped: the shapes go on with their
// first planes (maps as without the hypothesis), nothing fails, the run warns naming each mesh,
// and shapes.csv marks the shapes with -1.
TEST(Runner, ASecondPlaneThatFailsIsDroppedAndTheShapeGoesOn) {
  TempDir tmp;
  std::string config = WriteTestDataset(tmp.File("data"), 3);
  const RunResult plain = RunConfig(config, tmp.File("plain"), tmp.File("cache"));
  ASSERT_TRUE(plain.stats.ok());
  const std::string from = "symmetry: {type: test}";
  config.replace(config.find(from), from.size(),
                 "symmetry: {type: test, second: true, second_fails: true}");
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  ASSERT_TRUE(run.stats.ok());
  EXPECT_EQ(run.stats.shapes_computed, 3);
  EXPECT_EQ(Get(run.calls, "symmetry_second"), 3);
  EXPECT_EQ(Get(run.calls, "flip"), 6);
  EXPECT_EQ(ReadText(tmp.File("out/base/maps/s0_s1.map")),
            ReadText(tmp.File("plain/base/maps/s0_s1.map")));
  ASSERT_EQ(run.stats.warnings.size(), 3u);
  for (const std::string& warning : run.stats.warnings) {
    EXPECT_NE(warning.find(".off: second plane hypothesis dropped"), std::string::npos) << warning;
    EXPECT_NE(warning.find("no solution about this plane"), std::string::npos) << warning;
  }
  const std::vector<std::string> dropped = {"-1", "-1", "-1"};
  EXPECT_EQ(CsvColumn(ReadText(tmp.File("out/base/shapes.csv")), "second_plane"), dropped);
}

TEST(Runner, SecondIdenticalRunRecomputesNothing) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  const RunResult first = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  for (const char* kind : {"preprocess", "sampling", "geodesics", "embedding", "symmetry",
                           "symmetrize", "test_feature"}) {
    EXPECT_EQ(Get(first.calls, kind), 3) << kind;
    EXPECT_EQ(Get(first.stats.executed, kind), 3) << kind;
  }
  const auto before = Snapshot(tmp.File("out"));
  const RunResult second = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  for (const char* kind : {"preprocess", "sampling", "geodesics", "embedding", "symmetry",
                           "symmetrize", "test_feature"}) {
    EXPECT_EQ(Get(second.calls, kind), 0) << kind;
    EXPECT_EQ(Get(second.stats.executed, kind), 0) << kind;
  }
  // Nothing runs at all: every per-shape output and every pair's map and record come from the
  // cache, and D is not even read.
  EXPECT_TRUE(second.calls.empty());
  EXPECT_TRUE(second.stats.executed.empty());
  EXPECT_EQ(Get(second.stats.cache_hits, "geodesics"), 0);
  EXPECT_EQ(Get(second.stats.cache_hits, "symmetrize"), 3);
  EXPECT_EQ(Get(second.stats.cache_hits, "pair"), 6);
  EXPECT_EQ(second.stats.pairs_done, 6);
  EXPECT_EQ(Snapshot(tmp.File("out")), before);
  // With --resume as well, nothing at all runs.
  RunOptions resume;
  resume.resume = true;
  const RunResult third = RunConfig(config, tmp.File("out"), tmp.File("cache"), resume);
  EXPECT_TRUE(third.calls.empty());
  EXPECT_EQ(third.stats.pairs_skipped, 6);
  EXPECT_EQ(Snapshot(tmp.File("out")), before);
}

TEST(Runner, AProductOfNewOptionsIsComputedWithThePairs) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  RunConfig(config, tmp.File("out1"), tmp.File("cache"));
  testing::runner::TestFlip::feature_column = 1;
  const RunResult second = RunConfig(config, tmp.File("out2"), tmp.File("cache"));
  testing::runner::TestFlip::feature_column = 0;
  // The flip stage's product is new, what comes before it is not.
  EXPECT_EQ(Get(second.stats.executed, "test_feature"), 3);
  EXPECT_EQ(Get(second.stats.executed, "symmetrize"), 0);
  EXPECT_EQ(Get(second.stats.cache_hits, "pair"), 0);
  EXPECT_EQ(Get(second.calls, "flip"), 6);
  const RunResult third = RunConfig(config, tmp.File("out3"), tmp.File("cache"));
  EXPECT_TRUE(third.calls.empty());
}

TEST(Runner, VariantChangingALaterStageRecomputesNothingBeforeIt) {
  TempDir tmp;
  const std::string config =
      WriteTestDataset(tmp.File("data"), 3,
                       "variants:\n"
                       "  - {name: scaled, set: {pipeline.embedding.scale: 2.0}}\n"
                       "  - {name: flip1, set: {pipeline.flip.choose: 1}}\n");
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  EXPECT_TRUE(run.stats.ok());
  // preprocess, sampling and geodesics once per shape for all three variants.
  EXPECT_EQ(Get(run.calls, "preprocess"), 3);
  EXPECT_EQ(Get(run.calls, "sampling"), 3);
  EXPECT_EQ(Get(run.calls, "geodesics"), 3);
  // base and scaled differ from the embedding on; flip1 shares all of base's per-shape chain.
  EXPECT_EQ(Get(run.calls, "embedding"), 6);
  EXPECT_EQ(Get(run.calls, "symmetry"), 6);
  EXPECT_EQ(Get(run.calls, "symmetrize"), 6);
  // The flip stage's product of the embedding: base and scaled (new embedding); flip1 changes
  // an option the product does not name, so it shares base's.
  EXPECT_EQ(Get(run.calls, "test_feature"), 6);
  EXPECT_EQ(Get(run.stats.cache_hits, "test_feature"), 3);
  EXPECT_EQ(Get(run.stats.cache_hits, "geodesics"), 3);  // scaled reads base's D
  EXPECT_EQ(ReadText(tmp.File("out/comparison.txt")), "base\nscaled\nflip1\n");
  // flip1 chose candidate 1 (Rx(pi)); the oracle knows better.
  EXPECT_EQ(TestEvaluation::RecordBody(ReadText(tmp.File("out/flip1/pairs/s0_s1.rec"))).substr(0, 10),
            "s0 s1 1 0 ");
}

TEST(Runner, ResumeAfterAnInterruptionGivesTheSameOutputs) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  RunConfig(config, tmp.File("full"), tmp.File("cache"));
  const auto full = Snapshot(tmp.File("full"));
  RunConfig(config, tmp.File("out"), tmp.File("cache"));
  // What a kill leaves: some records missing, a map without its record, a temporary file,
  // no summaries.
  for (const char* stem : {"s0_s2", "s2_s0", "s2_s1"}) {
    fs::remove(tmp.File("out/base/pairs/") + stem + ".rec");
  }
  fs::remove(tmp.File("out/base/maps/s2_s1.map"));
  fs::remove_all(tmp.File("cache/pair"));  // so that the resumed pairs are computed again
  fs::remove(tmp.File("out/base/summary.txt"));
  fs::remove(tmp.File("out/base/failures.csv"));
  WriteText(tmp.File("out/base/pairs/s0_s2.rec.tmp.123.0"), "partial");
  RunOptions resume;
  resume.resume = true;
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"), resume);
  EXPECT_EQ(run.stats.pairs_skipped, 3);
  EXPECT_EQ(run.stats.pairs_done, 3);
  EXPECT_EQ(Get(run.calls, "flip"), 3);
  EXPECT_EQ(Snapshot(tmp.File("out")), full);
}

// Every way a kept pair can fail to prove itself: it is computed again, with a warning naming
// its record, and the outputs equal a fresh run on the current inputs.
TEST(Runner, ResumeComputesAgainWhatDoesNotProveItself) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  RunConfig(config, tmp.File("out"), tmp.File("cache"));
  const std::string out = tmp.File("out/base");
  // A truncated map, a deleted map, an unreadable record, a record without inputs.
  const std::string truncated = ReadText(out + "/maps/s0_s1.map");
  WriteText(out + "/maps/s0_s1.map", truncated.substr(0, truncated.size() / 2));
  fs::remove(out + "/maps/s0_s2.map");
  const std::string cut = ReadText(out + "/pairs/s1_s0.rec");
  WriteText(out + "/pairs/s1_s0.rec", cut.substr(0, cut.size() / 2));
  PairEvaluation record = ParsePairRecord(ReadText(out + "/pairs/s1_s2.rec"));
  ASSERT_TRUE(record.inputs);
  record.inputs.reset();
  WriteText(out + "/pairs/s1_s2.rec", SerializePairRecord(record));
  RunOptions resume;
  resume.resume = true;
  RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"), resume);
  EXPECT_EQ(run.stats.pairs_skipped, 2);
  EXPECT_EQ(run.stats.pairs_recomputed, 4);
  EXPECT_EQ(run.stats.pairs_done, 4);
  ASSERT_EQ(run.stats.warnings.size(), 4u);
  const std::string warnings = run.stats.warnings[0] + run.stats.warnings[1] +
                               run.stats.warnings[2] + run.stats.warnings[3];
  EXPECT_NE(warnings.find(out + "/pairs/s0_s1.rec: computed again: its map"), std::string::npos)
      << warnings;
  EXPECT_NE(warnings.find("s0_s2.map is missing"), std::string::npos) << warnings;
  EXPECT_NE(warnings.find(out + "/pairs/s1_s0.rec: computed again: unreadable record"),
            std::string::npos)
      << warnings;
  EXPECT_NE(warnings.find("carries no inputs"), std::string::npos) << warnings;
  RunConfig(config, tmp.File("fresh"), tmp.File("cache"));
  EXPECT_EQ(Snapshot(tmp.File("out")), Snapshot(tmp.File("fresh")));

  // A mesh replaced after the run: every pair of that shape is computed again.
  WriteText(tmp.File("data/shapes/s1.off"), ReadText(tmp.File("data/shapes/s2.off")));
  run = RunConfig(config, tmp.File("out"), tmp.File("cache"), resume);
  EXPECT_EQ(run.stats.pairs_skipped, 2);
  EXPECT_EQ(run.stats.pairs_recomputed, 4);
  ASSERT_FALSE(run.stats.warnings.empty());
  EXPECT_NE(run.stats.warnings[0].find("mesh or a per-shape option changed"), std::string::npos)
      << run.stats.warnings[0];
  RunConfig(config, tmp.File("fresh2"), tmp.File("cache2"));
  EXPECT_EQ(Snapshot(tmp.File("out")), Snapshot(tmp.File("fresh2")));
}

// A record under the name of another pair (as runs whose pair file names collided left them)
// is computed again, saying whose record it holds.
TEST(Runner, ResumeComputesAgainAPairWhoseFileHoldsAnotherPairsRecord) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 2);
  RunConfig(config, tmp.File("out"), tmp.File("cache"));
  const std::string out = tmp.File("out/base");
  const std::string s0_s1 = ReadText(out + "/pairs/s0_s1.rec");
  WriteText(out + "/pairs/s0_s1.rec", ReadText(out + "/pairs/s1_s0.rec"));
  WriteText(out + "/pairs/s1_s0.rec", s0_s1);
  RunOptions resume;
  resume.resume = true;
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"), resume);
  EXPECT_EQ(run.stats.pairs_skipped, 0);
  EXPECT_EQ(run.stats.pairs_recomputed, 2);
  ASSERT_EQ(run.stats.warnings.size(), 2u);
  EXPECT_NE(run.stats.warnings[0].find(out + "/pairs/s0_s1.rec: computed again: it holds the "
                                             "record of s1 -> s0"),
            std::string::npos)
      << run.stats.warnings[0];
  RunConfig(config, tmp.File("fresh"), tmp.File("cache"));
  EXPECT_EQ(Snapshot(tmp.File("out")), Snapshot(tmp.File("fresh")));
}

TEST(Runner, AVariantFolderIsMarkedInProgressUntilItsSummaryIsWritten) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 2);
  RunConfig(config, tmp.File("out"), tmp.File("cache"));
  EXPECT_FALSE(fs::exists(tmp.File("out/base/IN_PROGRESS")));
  EXPECT_NO_THROW(RequireNotInProgress(tmp.File("out/base")));
  // A run that dies before its summary is written leaves the marker.
  TestEvaluation throwing;
  throwing.throw_in_write = true;
  EXPECT_THROW(RunConfig(config, tmp.File("out"), tmp.File("cache"), {}, &throwing), IoError);
  EXPECT_TRUE(fs::exists(tmp.File("out/base/IN_PROGRESS")));
  try {
    RequireNotInProgress(tmp.File("out/base"));
    ADD_FAILURE() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find(tmp.File("out/base") + ": the folder is incomplete"),
              std::string::npos)
        << e.what();
  }
  TestEvaluation evaluation;
  EXPECT_THROW(MergeRuns({tmp.File("out")}, tmp.File("merged"), evaluation), InvalidInputError);
  RunOptions resume;
  resume.resume = true;
  RunConfig(config, tmp.File("out"), tmp.File("cache"), resume);
  EXPECT_FALSE(fs::exists(tmp.File("out/base/IN_PROGRESS")));
  EXPECT_TRUE(MergeRuns({tmp.File("out")}, tmp.File("merged"), evaluation).empty());
  EXPECT_FALSE(fs::exists(tmp.File("merged/base/IN_PROGRESS")));
}

TEST(Runner, ACacheThatIsAFileAndADatasetWithoutPairsAreErrors) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 2);
  WriteText(tmp.File("cache_file"), "not a folder");
  try {
    RunConfig(config, tmp.File("out"), tmp.File("cache_file"));
    ADD_FAILURE() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find(tmp.File("cache_file") + ": the cache must be a folder"),
              std::string::npos)
        << e.what();
  }
  const std::string one_shape = WriteTestDataset(tmp.File("data1"), 1);
  try {
    RunConfig(one_shape, tmp.File("out1"), tmp.File("cache"));
    ADD_FAILURE() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("variant base: the dataset"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("has no pairs to run"), std::string::npos) << e.what();
  }
}

TEST(Runner, ResumeRefusesAChangedConfig) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 2);
  RunConfig(config, tmp.File("out"), tmp.File("cache"));
  RunOptions resume;
  resume.resume = true;
  const std::string changed = config + "variants: []\n";
  EXPECT_NO_THROW(RunConfig(changed, tmp.File("out"), tmp.File("cache"), resume));
  // The same config named by another path (scripts pass absolute ones) resumes.
  EXPECT_NO_THROW(RunConfig(config, tmp.File("out"), tmp.File("cache"), resume, nullptr,
                            "/abs/path/to/test.yaml"));
  std::string other = config;
  other.replace(other.find("count: 6"), 8, "count: 7");
  EXPECT_THROW(RunConfig(other, tmp.File("out"), tmp.File("cache"), resume), ConfigError);
}

TEST(Runner, ShardsMergedEqualASingleRun) {
  TempDir tmp;
  const std::string config = WriteTestDataset(
      tmp.File("data"), 4, "variants:\n  - {name: flip1, set: {pipeline.flip.choose: 1}}\n");
  RunConfig(config, tmp.File("single"), tmp.File("cache"));
  int pairs = 0;
  const std::vector<std::string> shards =
      RunShards(tmp, 3, [&](const std::string& out, const RunOptions& shard) {
        pairs += RunConfig(config, out, tmp.File("cache"), shard).stats.pairs_total;
      });
  EXPECT_EQ(pairs, 2 * 12);  // every pair in exactly one shard, both variants
  TestEvaluation evaluation;
  EXPECT_TRUE(MergeRuns(shards, tmp.File("merged"), evaluation).empty());
  EXPECT_EQ(Snapshot(tmp.File("merged")), Snapshot(tmp.File("single")));
}

// The cluster split of `symembed slurm`: shapes-only shards fill the cache, each shape in one
// of them and nothing else written; then pair shards split by target find every shape cached
// and merge to the single run.
TEST(Runner, ShapesOnlyShardsThenTargetShardsComputeEachShapeOnceAndEqualASingleRun) {
  TempDir tmp;
  const std::string config = WriteTestDataset(
      tmp.File("data"), 5, "variants:\n  - {name: scaled, set: {pipeline.embedding.scale: 2.0}}\n");
  RunConfig(config, tmp.File("single"), tmp.File("single_cache"));
  std::map<std::string, int> computed;  // shape -> shapes-only shards that computed it
  for (int i = 0; i < 2; ++i) {
    RunOptions shapes;
    shapes.shapes_only = true;
    shapes.shard_index = i;
    shapes.shard_count = 2;
    shapes.on_shape = [&](const std::string& shape, const std::string& variant,
                          const std::vector<std::string>& stages, const std::string&) {
      if (variant == "base") {
        // preprocess ... symmetrize, the second plane (none here), the flip's product
        EXPECT_EQ(stages.size(), 8u) << shape;
        ++computed[shape];
      }
    };
    const RunResult run = RunConfig(config, tmp.File("none"), tmp.File("cache"), shapes);
    EXPECT_TRUE(run.stats.ok());
    EXPECT_EQ(run.stats.pairs_total, 0);
    EXPECT_EQ(Get(run.calls, "flip"), 0);
    EXPECT_EQ(Get(run.stats.executed, "pair"), 0);
  }
  EXPECT_FALSE(fs::exists(tmp.File("none")));  // no pair outputs, no folder at all
  EXPECT_EQ(computed,
            (std::map<std::string, int>{{"s0", 1}, {"s1", 1}, {"s2", 1}, {"s3", 1}, {"s4", 1}}));

  const std::vector<std::string> shards = RunShards(
      tmp, 3,
      [&](const std::string& out, const RunOptions& shard) {
        const RunResult run = RunConfig(config, out, tmp.File("cache"), shard);
        for (const char* kind : {"preprocess", "sampling", "geodesics", "embedding", "symmetry",
                                 "symmetrize", "test_feature"}) {
          EXPECT_EQ(Get(run.stats.executed, kind), 0) << kind << " in " << out;
        }
      },
      ShardSplit::kTarget);
  TestEvaluation evaluation;
  EXPECT_TRUE(MergeRuns(shards, tmp.File("merged"), evaluation).empty());
  EXPECT_EQ(Snapshot(tmp.File("merged")), Snapshot(tmp.File("single")));
}

TEST(Runner, ShapesOnlyNeedsACache) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 2);
  RunOptions shapes;
  shapes.shapes_only = true;
  EXPECT_THROW(RunConfig(config, tmp.File("out"), "", shapes), ConfigError);
}

TEST(Runner, BadMeshIsRecordedAndTheRunGoesOn) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  WriteText(tmp.File("data/shapes/s1.off"), "OFF\n3 1 0\n0 0 0\n");  // truncated
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  EXPECT_FALSE(run.stats.ok());
  EXPECT_EQ(run.stats.pairs_done, 2);  // s0 <-> s2
  const std::string failures = ReadText(tmp.File("out/base/failures.csv"));
  EXPECT_NE(failures.find("pair,s0,s1,shape 's1' failed"), std::string::npos) << failures;
  EXPECT_NE(failures.find("shape,s1,,"), std::string::npos) << failures;
  EXPECT_NE(failures.find("truncated OFF mesh"), std::string::npos) << failures;
  EXPECT_EQ(run.stats.failures.size(), 5u);  // the shape and its four pairs
  const std::string summary = ReadText(tmp.File("out/base/summary.txt"));
  EXPECT_NE(summary.find("s0->s2: {\"inputs\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("s1->s0: failed"), std::string::npos);
  EXPECT_NE(summary.find("failures 5"), std::string::npos);
  // Shard + merge reproduces the failures too.
  const std::vector<std::string> shards =
      RunShards(tmp, 2, [&](const std::string& out, const RunOptions& shard) {
        RunConfig(config, out, tmp.File("cache"), shard);
      });
  TestEvaluation evaluation;
  EXPECT_EQ(MergeRuns(shards, tmp.File("merged"), evaluation).size(), 5u);
  EXPECT_EQ(Snapshot(tmp.File("merged")), Snapshot(tmp.File("out")));
}

TEST(Runner, EvaluationFailureIsRecordedWithoutARecord) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 3);
  TestEvaluation evaluation;
  evaluation.fail_source = "s2";
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"), {}, &evaluation);
  EXPECT_EQ(run.stats.failures.size(), 2u);
  EXPECT_FALSE(fs::exists(tmp.File("out/base/pairs/s2_s0.rec")));
  EXPECT_TRUE(fs::exists(tmp.File("out/base/maps/s2_s0.map")));
  EXPECT_NE(ReadText(tmp.File("out/base/failures.csv")).find("pair,s2,s0,evaluation refused s2"),
            std::string::npos);
}

TEST(Runner, DamagedCacheEntryIsRecomputed) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 2);
  RunConfig(config, tmp.File("out"), tmp.File("cache"));
  int damaged = 0;
  for (const auto& e : fs::directory_iterator(tmp.File("cache/embedding"))) {
    const std::string bytes = ReadText(e.path().string());
    WriteText(e.path().string(), bytes.substr(0, bytes.size() / 2));
    ++damaged;
  }
  EXPECT_EQ(damaged, 2);
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  EXPECT_EQ(Get(run.calls, "embedding"), 2);
  EXPECT_EQ(Get(run.calls, "geodesics"), 0);  // D comes from the cache
  EXPECT_EQ(Get(run.calls, "symmetry"), 0);
}

TEST(Runner, UnknownVariantAndBadShardAreErrors) {
  TempDir tmp;
  const std::string config = WriteTestDataset(tmp.File("data"), 2);
  RunOptions options;
  options.variant = "nope";
  EXPECT_THROW(RunConfig(config, tmp.File("out"), "", options), ConfigError);
  RunOptions shard;
  shard.shard_index = 2;
  shard.shard_count = 2;
  EXPECT_THROW(RunConfig(config, tmp.File("out"), "", shard), ConfigError);
}

// evaluation.refine_start: ground_truth hands the refine stage the ground truth instead of the
// matching stage's map: with a wrong rotation (flip choose 2) the pipeline's map is not the
// identity, the ground truth's is, and the identity refine stage keeps it. Both variants share
// one cache, so the pair key must tell them apart.
TEST(Runner, RefineStartGroundTruthStartsTheRefinementFromTheTruth) {
  TempDir tmp;
  const std::string config = WriteTestDataset(
      tmp.File("data"), 2,
      "variants:\n"
      "  - {name: wrong, set: {pipeline.flip.choose: 2}}\n"
      "  - {name: truth, set: {pipeline.flip.choose: 2, evaluation.refine_start: ground_truth}}\n");
  const RunResult run = RunConfig(config, tmp.File("out"), tmp.File("cache"));
  EXPECT_TRUE(run.stats.ok());
  std::string identity;
  for (int v = 1; v <= 20; ++v) identity += std::to_string(v) + "\n";
  EXPECT_EQ(ReadText(tmp.File("out/base/maps/s0_s1.map")), identity);
  EXPECT_NE(ReadText(tmp.File("out/wrong/maps/s0_s1.map")), identity);
  EXPECT_EQ(ReadText(tmp.File("out/truth/maps/s0_s1.map")), identity);
  EXPECT_EQ(ReadText(tmp.File("out/truth/maps/s1_s0.map")), identity);
  EXPECT_NE(ReadText(tmp.File("out/truth/config.yaml")).find("refine_start: ground_truth"),
            std::string::npos);
}

// Lined vertices take their first line's target; the others that of the lined vertex nearest
// along the edges, or the Euclidean nearest off the lined vertices' part of the surface.
TEST(MapFromGroundTruth, FillsUnlinedVerticesFromTheNearestLinedOne) {
  Surface grid = GridMesh(5, 4);  // vertex v at column v % 5, row v / 5
  grid.V.conservativeResize(21, 3);
  grid.V.row(20) = grid.V.row(4) + Eigen::RowVector3d(0.01, 0.0, 0.3);  // on no face
  PreprocessedGroundTruth truth;
  truth.source_ids = {0, 4, 0};
  truth.target_ids = {7, 9, 3};
  const std::vector<int> map = MapFromGroundTruth(grid, 10, truth);
  ASSERT_EQ(map.size(), 21u);
  EXPECT_EQ(map[0], 7);  // the first of its two lines
  EXPECT_EQ(map[4], 9);
  EXPECT_EQ(map[1], 7);
  EXPECT_EQ(map[3], 9);
  EXPECT_EQ(map[15], 7);  // three rows up from vertex 0
  EXPECT_EQ(map[19], 9);
  EXPECT_EQ(map[20], 9);  // unreached along edges: the Euclidean nearest lined vertex
  EXPECT_THROW(MapFromGroundTruth(grid, 10, PreprocessedGroundTruth{}), InvalidInputError);
  truth.target_ids[1] = 10;
  try {
    MapFromGroundTruth(grid, 10, truth);
    FAIL() << "a target id out of range was accepted";
  } catch (const InvalidInputError& error) {
    EXPECT_NE(std::string(error.what()).find("line 2"), std::string::npos) << error.what();
  }
}

TEST(Runner, RemovedInputVerticesTakeTheNearestKeptVertex) {
  Eigen::MatrixX3d V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0.9, 0.1, 0, 5, 5, 5;
  std::vector<int> kept, nearest;
  InputToKept(V, {0, 1}, &kept, &nearest);
  EXPECT_EQ(kept, (std::vector<int>{0, 1, -1, -1}));
  EXPECT_EQ(nearest, (std::vector<int>{0, 1, 1, 1}));
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

TEST(Runner, CacheKeysIgnoreThreadCounts) {
  testing::runner::TestSampling a(3), b(3);
  a.set_resolved_options(
      YAML::Load("{type: x, count: 3, threads: 4, common: {threads: 2, precision: float}}"));
  b.set_resolved_options(
      YAML::Load("{type: x, count: 3, threads: 1, common: {threads: 8, precision: float}}"));
  EXPECT_EQ(OptionsText(a), OptionsText(b));
  EXPECT_EQ(OptionsText(a).find("threads"), std::string::npos);
  EXPECT_NE(OptionsText(a).find("precision: float"), std::string::npos) << OptionsText(a);
}

}  // namespace
}  // namespace symembed

#include "eval/evaluator.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>

#include "core/parallel.h"
#include "core/primitives.h"
#include "tests/eval/euclidean_geodesics.h"

namespace symembed {
namespace {

using testing::EuclideanGeodesics;

// 5 x 5 grid on [0, 4]^2: vertex id = 5 y + x, area 16, so errors are distances / 4.
constexpr int kN = 5;
int Id(int x, int y) { return y * kN + x; }

PreprocessResult Identity(const Surface& s) {
  PreprocessResult pre;
  pre.surface = s;
  for (int v = 0; v < s.NumVertices(); ++v) pre.input_ids.push_back(v);
  return pre;
}

// Ground truth: every vertex to itself; symmetric ground truth: mirrored in x (x -> 4 - x).
InputGroundTruth GridTruth() {
  InputGroundTruth gt;
  for (int y = 0; y < kN; ++y) {
    for (int x = 0; x < kN; ++x) {
      gt.source_ids.push_back(Id(x, y));
      gt.target_ids.push_back(Id(x, y));
      gt.target_sym_ids.push_back(Id(kN - 1 - x, y));
    }
  }
  return gt;
}

std::vector<int> MapOf(int (*f)(int, int)) {
  std::vector<int> map(kN * kN);
  for (int y = 0; y < kN; ++y) {
    for (int x = 0; x < kN; ++x) map[Id(x, y)] = f(x, y);
  }
  return map;
}

class EvaluatorTest : public ::testing::Test {
 protected:
  EvaluatorTest() : shape_(MakeEvalShape(Identity(GridMesh(kN, kN, 4.0, 4.0)), kN * kN)) {}
  EuclideanGeodesics geodesics_;
  EvalShape shape_;
};

// Distances and areas here are sums of a few exact terms.
constexpr double kTol = 1e-6;  // distances pass through float in the cache

TEST_F(EvaluatorTest, GroundTruthMapScoresZeroWithoutFlip) {
  Evaluator evaluator(EvaluationOptions{}, geodesics_);
  const auto p = evaluator.Evaluate("a", "b", shape_, MapOf([](int x, int y) { return Id(x, y); }),
                                    GridTruth());
  ASSERT_TRUE(p.ok) << p.message;
  EXPECT_EQ(p.points, 25);
  EXPECT_NEAR(p.mean_direct, 0.0, kTol);
  EXPECT_NEAR(p.max_direct, 0.0, kTol);
  EXPECT_DOUBLE_EQ(p.pct_direct[0], 100.0);
  // Against the mirror: |2x - 4| / 4 averaged over x = 0..4 = (1 + 0.5 + 0 + 0.5 + 1) / 5.
  EXPECT_NEAR(p.mean_sym, 0.6, kTol);
  EXPECT_EQ(p.flip, FlipClass::kNone);
  EXPECT_GE(p.stage_seconds.at("evaluation"), 0.0);
}

TEST_F(EvaluatorTest, MirroredMapIsLeftRight) {
  Evaluator evaluator(EvaluationOptions{}, geodesics_);
  const auto p = evaluator.Evaluate(
      "a", "b", shape_, MapOf([](int x, int y) { return Id(kN - 1 - x, y); }), GridTruth());
  ASSERT_TRUE(p.ok) << p.message;
  EXPECT_NEAR(p.mean_direct, 0.6, kTol);
  EXPECT_NEAR(p.mean_sym, 0.0, kTol);
  EXPECT_NEAR(p.mean_flip_tolerant, 0.0, kTol);
  EXPECT_EQ(p.flip, FlipClass::kLeftRight);
}

TEST_F(EvaluatorTest, HandComputedShiftAndCandidateFlips) {
  Evaluator evaluator(EvaluationOptions{}, geodesics_);
  // x -> min(x + 1, 4): error 1/4 at x = 0..3, 0 at x = 4; mean 0.2, median 0.25.
  const auto p = evaluator.Evaluate("a", "b", shape_,
                                    MapOf([](int x, int y) { return Id(std::min(x + 1, 4), y); }),
                                    GridTruth(), /*chosen=*/1, /*oracle=*/0);
  ASSERT_TRUE(p.ok) << p.message;
  EXPECT_NEAR(p.mean_direct, 0.2, kTol);
  EXPECT_NEAR(p.median_direct, 0.25, kTol);
  EXPECT_NEAR(p.max_direct, 0.25, kTol);
  EXPECT_DOUBLE_EQ(p.pct_direct[0], 20.0);   // only x = 4 is within 0.05
  EXPECT_DOUBLE_EQ(p.pct_direct[2], 100.0);  // 0.25 <= 0.25
  EXPECT_EQ(p.flip, FlipClass::kUpDown);     // chosen Rx against the oracle's I
  EXPECT_EQ(p.chosen, 1);
  EXPECT_EQ(p.oracle, 0);
  const double mean = evaluator.MeanError(
      "b", shape_, MapOf([](int x, int y) { return Id(std::min(x + 1, 4), y); }), GridTruth());
  EXPECT_NEAR(mean, 0.2, kTol);
}

// The oracle's time is split from the ground-truth distances it triggers: the first call for a
// target reports the time of the rows it computed, a call that finds them all cached exactly 0,
// and the error is the same either way.
TEST_F(EvaluatorTest, MeanErrorReportsTheTimeOfTheRowsItComputed) {
  Evaluator evaluator(EvaluationOptions{}, geodesics_);
  const auto map = MapOf([](int x, int y) { return Id(std::min(x + 1, 4), y); });
  double first = -1.0, second = -1.0;
  const double a = evaluator.MeanError("b", shape_, map, GridTruth(), &first);
  const int64_t rows = evaluator.RowsComputed();
  const double b = evaluator.MeanError("b", shape_, map, GridTruth(), &second);
  EXPECT_GT(rows, 0);
  EXPECT_EQ(evaluator.RowsComputed(), rows);  // nothing computed the second time
  EXPECT_GT(first, 0.0);
  EXPECT_EQ(second, 0.0);
  EXPECT_EQ(a, b);
  EXPECT_NEAR(a, 0.2, kTol);
}

TEST_F(EvaluatorTest, ConstantMapScoresBadly) {
  Evaluator evaluator(EvaluationOptions{}, geodesics_);
  const auto p =
      evaluator.Evaluate("a", "b", shape_, MapOf([](int, int) { return Id(0, 0); }), GridTruth());
  ASSERT_TRUE(p.ok) << p.message;
  double expected = 0.0;
  for (int y = 0; y < kN; ++y) {
    for (int x = 0; x < kN; ++x) expected += std::hypot(x, y) / 4.0 / (kN * kN);
  }
  EXPECT_NEAR(p.mean_direct, expected, kTol);
  EXPECT_GT(p.mean_direct, 0.5);
  EXPECT_DOUBLE_EQ(p.pct_direct[0], 4.0);  // only the corner itself
}

TEST_F(EvaluatorTest, MapsThatDoNotFitFailThePairWithoutThrowing) {
  Evaluator evaluator(EvaluationOptions{}, geodesics_);
  std::vector<int> short_map(10, 0);
  const auto p = evaluator.Evaluate("a", "b", shape_, short_map, GridTruth());
  EXPECT_FALSE(p.ok);
  EXPECT_NE(p.message.find("outside the map"), std::string::npos) << p.message;
  std::vector<int> bad(kN * kN, 0);
  bad[3] = 99;
  const auto q = evaluator.Evaluate("a", "b", shape_, bad, GridTruth());
  EXPECT_FALSE(q.ok);
  EXPECT_NE(q.message.find("map entry 99 out of range"), std::string::npos) << q.message;
  EXPECT_FALSE(evaluator.Evaluate("a", "b", shape_, bad, InputGroundTruth{}).ok);
}

TEST_F(EvaluatorTest, DistancesAreComputedOncePerTargetAndSourceSet) {
  Evaluator evaluator(EvaluationOptions{}, geodesics_);
  const auto identity = MapOf([](int x, int y) { return Id(x, y); });
  evaluator.Evaluate("a", "b", shape_, identity, GridTruth());
  // Ground-truth points are the sources (the map's image is not smaller than half of them).
  EXPECT_EQ(evaluator.RowsComputed(), 25);
  evaluator.Evaluate("c", "b", shape_, MapOf([](int x, int y) { return Id(4 - x, y); }),
                     GridTruth());
  EXPECT_EQ(evaluator.RowsComputed(), 25);  // all cached
  // A constant map needs one row (its image) and that is what is computed.
  evaluator.Evaluate("a", "other", shape_, MapOf([](int, int) { return 7; }), GridTruth());
  EXPECT_EQ(evaluator.RowsComputed(), 26);
  EXPECT_EQ(geodesics_.solves.load(), 26);
}

TEST_F(EvaluatorTest, ThreadedEvaluationMatchesSerial) {
  std::vector<std::vector<int>> maps;
  for (int shift = 0; shift < 12; ++shift) {
    std::vector<int> m(kN * kN);
    for (int v = 0; v < kN * kN; ++v) m[v] = (v * (shift + 1) + shift) % (kN * kN);
    maps.push_back(m);
  }
  Evaluator serial(EvaluationOptions{}, geodesics_);
  Evaluator threaded(EvaluationOptions{}, geodesics_, /*cache_budget_mb=*/0.001);
  std::vector<PairEvaluation> expected, actual(maps.size());
  for (size_t i = 0; i < maps.size(); ++i) {
    expected.push_back(
        serial.Evaluate("a", "t" + std::to_string(i % 3), shape_, maps[i], GridTruth()));
  }
  ParallelFor(
      static_cast<int>(maps.size()),
      [&](int i) {
        actual[i] =
            threaded.Evaluate("a", "t" + std::to_string(i % 3), shape_, maps[i], GridTruth());
      },
      4);
  for (size_t i = 0; i < maps.size(); ++i) {
    EXPECT_EQ(actual[i].errors_direct, expected[i].errors_direct) << i;
    EXPECT_EQ(actual[i].errors_sym, expected[i].errors_sym) << i;
  }
}

TEST_F(EvaluatorTest, PointsSelectsFarthestGroundTruthPoints) {
  EvaluationOptions options;
  options.points = 4;
  const InputGroundTruth selected = SelectPoints(GridTruth(), shape_, 4);
  // From corner (0,0): (4,4), then (4,0) (lower line index than (0,4)), then (0,4).
  EXPECT_EQ(selected.target_ids, (std::vector<int>{Id(0, 0), Id(4, 0), Id(0, 4), Id(4, 4)}));
  EXPECT_EQ(selected.target_sym_ids.size(), 4u);
  Evaluator evaluator(options, geodesics_);
  const auto p =
      evaluator.Evaluate("a", "b", shape_, MapOf([](int, int) { return Id(0, 0); }), GridTruth());
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.points, 4);
  EXPECT_NEAR(p.mean_direct, (0 + 1 + 1 + std::sqrt(2.0)) / 4, kTol);
}

TEST(EvalShape, RemovedVerticesMapToTheNearestKeptVertex) {
  const Surface input = GridMesh(3, 2, 2.0, 1.0);  // ids: (x, y) -> 3 y + x
  PreprocessResult pre;
  // Keep 0, 1, 3, 4 (the first two columns), scaled by 2; vertices 2 and 5 removed.
  pre.surface.V = Eigen::MatrixX3d(4, 3);
  pre.surface.V << 0, 0, 0, 2, 0, 0, 0, 2, 0, 2, 2, 0;
  pre.surface.F = Eigen::MatrixX3i(2, 3);
  pre.surface.F << 0, 1, 3, 0, 3, 2;
  pre.input_ids = {0, 1, 3, 4};
  pre.scale = 2.0;
  const EvalShape shape = MakeEvalShape(pre, input);
  EXPECT_EQ(shape.vertex_of_input, (std::vector<int>{0, 1, 1, 2, 3, 3}));
  EXPECT_NEAR(shape.area, 4.0, 1e-12);  // exact unit square scaled by 2
  EXPECT_THROW(MakeEvalShape(pre, 6), InvalidInputError);
}

}  // namespace
}  // namespace symembed

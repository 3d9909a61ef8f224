#include <gtest/gtest.h>

#include "core/canonical_frame.h"
#include "core/errors.h"
#include "registry/registry.h"
#include "stages/flip/extrinsic.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

ShapeData MakeShape(const std::string& name, const Surface& surface) {
  ShapeData shape;
  shape.name = name;
  shape.surface = surface;
  shape.Y = CanonicalFrame(surface.V);
  return shape;
}

PairGroundTruth IdentityGroundTruth(int n) {
  PairGroundTruth gt;
  for (int i = 0; i < n; ++i) {
    gt.source_ids.push_back(i);
    gt.target_ids.push_back(i);
  }
  return gt;
}

// Source: the figure; target: a second pose (same vertex ids). For each candidate j the target's
// canonical embedding is turned by R_j, so the right answer moves with j: candidates form the
// Klein four-group and (with the index order I, Rx, Ry, Rz) R_a R_b = R_(a xor b).
class FlipScorers : public ::testing::TestWithParam<std::string> {};

TEST_P(FlipScorers, RecoverEveryCandidateRotation) {
  Registry registry;
  RegisterBuiltinStages(registry);
  auto stage = registry.CreateAs<FlipStage>("flip", YAML::Load("{type: " + GetParam() + "}"),
                                            "t.yaml", "pipeline.flip");
  ShapeData source = MakeShape("rest", testing::SymmetricFigure());
  const ShapeData posed = MakeShape("posed", testing::PosedSymmetricFigure(1, 0.5, 0.2));
  const PairGroundTruth gt = IdentityGroundTruth(source.surface.NumVertices());
  stage->PrepareShape(source);
  // The right candidate for the unturned target, from the ground truth.
  auto oracle = registry.CreateAs<FlipStage>("flip", YAML::Load("{type: oracle}"), "t.yaml", "f");
  const int base = oracle->Run(PairInput{source, posed, &gt}).chosen;
  const auto rotations = CandidateRotations();
  for (int j = 0; j < 4; ++j) {
    ShapeData target = posed;
    target.Y = posed.Y * rotations[j];  // rows R_j y (R_j is symmetric)
    stage->PrepareShape(target);
    const FlipResult r = stage->Run(PairInput{source, target, &gt});
    EXPECT_EQ(r.chosen, base ^ j) << GetParam() << " candidate " << j << ": " << r.status.message;
  }
}

INSTANTIATE_TEST_SUITE_P(All, FlipScorers,
                         ::testing::Values("extrinsic", "chamfer", "hks", "oracle"));

TEST(OracleFlip, RefusesWithoutGroundTruth) {
  Registry registry;
  RegisterBuiltinStages(registry);
  auto stage = registry.CreateAs<FlipStage>("flip", YAML::Load("{type: oracle}"), "t.yaml", "f");
  const ShapeData shape = MakeShape("rest", testing::SymmetricFigure());
  try {
    stage->Run(PairInput{shape, shape, nullptr});
    FAIL() << "oracle ran without ground truth";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("no ground truth"), std::string::npos) << e.what();
  }
}

TEST(ExtrinsicFlip, FeaturesAreScaleFreeAndInRange) {
  const Surface figure = testing::SymmetricFigure();
  Surface scaled = figure;
  scaled.V *= 3.0;
  const Eigen::MatrixXd a = ExtrinsicFeatures(figure, 2), b = ExtrinsicFeatures(scaled, 2);
  ASSERT_EQ(a.rows(), figure.NumVertices());
  // Shape index and sqrt(area)-scaled curvedness do not change with scale (rounding, amplified
  // by atan2 near flat vertices).
  EXPECT_NEAR((a - b).cwiseAbs().maxCoeff(), 0.0, 1e-6);
  EXPECT_LE(a.col(0).cwiseAbs().maxCoeff(), 1.0);
  EXPECT_NEAR(a.col(2).sum(), 1.0, 1e-12);
}

TEST(ExtrinsicFlip, MissingFeaturesFailClearly) {
  Registry registry;
  RegisterBuiltinStages(registry);
  auto stage = registry.CreateAs<FlipStage>("flip", YAML::Load("{type: extrinsic}"), "t.yaml", "f");
  const ShapeData shape = MakeShape("rest", testing::SymmetricFigure());
  EXPECT_THROW(stage->Run(PairInput{shape, shape, nullptr}), InvalidInputError);
}

}  // namespace
}  // namespace symembed

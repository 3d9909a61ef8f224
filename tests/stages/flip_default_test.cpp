// The flip stage's default (the refined_maps term alone) against its former default (curvature,
// descriptor and orientation terms with the refined front-back decision) on a non-isometric
// pair of the generator: humanoid poses 0 and 8 with bones stretched and thickened (factors in
// [0.85, 1.15]), each run through the per-shape stages' defaults but a symmetrization of
// weight 1 (a strong one settles this pair's front and back for either scorer). The features of
// the former terms change with the body's proportions and choose the rotation turned by pi about the
// vertical axis, which maps the front onto the back; the refined maps' distortion and curvature
// disagreement keep the right one.
#include <gtest/gtest.h>

#include <string>

#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"
#include "tests/stages/chain_test_util.h"
#include "tests/stages/flip_test_util.h"

namespace symembed {
namespace {

constexpr char kSymmetrize[] = "{type: ceres, symmetry_weight: 1}";

TEST(FlipDefault, RefinedMapsKeepTheFrontOfAStretchedHumanoidWhereTheFormerTermsDoNot) {
  SynthOptions o;
  o.poses = 10;
  o.nonisometric = 0.15;
  o.seed = 1;
  const SynthClass cls = GenerateClass(FigureKind::kHumanoid, o);
  ShapeData source = testing::RunDefaultShapeStages("humanoid0", cls.shapes[0].shape.surface,
                                                     "{type: plane2d}", kSymmetrize);
  ShapeData target = testing::RunDefaultShapeStages("humanoid8", cls.shapes[8].shape.surface,
                                                     "{type: plane2d}", kSymmetrize);
  // Ground truth: the generator's rest vertex ids.
  const PreprocessedGroundTruth gt = testing::RestGroundTruth(
      cls.shapes[0].shape, cls.shapes[8].shape, cls.rest.surface.NumVertices());
  Registry r;
  RegisterBuiltinStages(r);
  const auto chosen_by = [&](const std::string& yaml) {
    const auto stage = testing::MakeStageAs<FlipStage>(r, "flip", yaml);
    ShapeData s = source, t = target;
    ComputeNeeds(stage->Needs(), &s);
    ComputeNeeds(stage->Needs(), &t);
    return stage->Run(PairInput{s, t, &gt});
  };
  const int oracle = chosen_by("{type: oracle}").chosen;
  const FlipResult now = chosen_by("{type: extrinsic}");
  const FlipResult former = chosen_by(testing::kFormerDefault);
  EXPECT_EQ(now.chosen, oracle) << now.status.message;
  // The failure mode the default removes: the former terms turn the body front to back (the
  // candidate differing from the oracle's by pi about y).
  const Eigen::Matrix3d relative =
      CandidateRotations()[former.chosen].transpose() * CandidateRotations()[oracle];
  EXPECT_TRUE(relative.isApprox(CandidateRotations()[2])) << former.status.message;
}

}  // namespace
}  // namespace symembed

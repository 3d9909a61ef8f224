// The symmetry stage's defaults on a quadruped whose geodesic distances favour a wrong plane.
//
// A non-isometric quadruped (bones stretched and thickened per pose) has, besides its left-right
// symmetry, an approximate front-back one (front legs to hind legs) and a near-identity one
// (back to belly across the thin body), and its distances and its 2D embedding can prefer either
// of them. The low Laplace-Beltrami eigenfunctions still tell the left-right symmetry apart: this
// is the failure the spectral check must catch by default, whatever the check's threshold would
// have said of the plane chosen by distances.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "eval/synthetic/synthetic.h"
#include "harness/shape_pipeline.h"
#include "tests/stages/chain_test_util.h"

namespace symembed {
namespace {

// SymmetryGroundTruthError of the canonical embedding of pose `pose` of the class, the stages
// from sampling to symmetrize at their defaults but for the symmetry stage's `symmetry` YAML.
double PlaneError(const SynthClass& cls, int pose, const std::string& symmetry,
                  std::string* message) {
  const TrackedSurface& shape = cls.shapes[pose].shape;
  const ShapeData data = testing::RunDefaultShapeStages("pose", shape.surface, symmetry);
  *message = data.symmetry.status.message;
  const Eigen::MatrixX3d& Y = data.Y;

  const std::vector<int> of_rest = testing::VertexOfRest(shape, cls.rest.surface.NumVertices());
  std::vector<int> ids, sym_ids;
  for (size_t v = 0; v < shape.rest_ids.size(); ++v) {
    const int mirror = of_rest[cls.rest.mirror[shape.rest_ids[v]]];
    if (mirror < 0) continue;
    ids.push_back(static_cast<int>(v));
    sym_ids.push_back(mirror);
  }
  return SymmetryGroundTruthError(Y, ids, sym_ids);
}

SynthClass StretchedQuadrupeds() {
  SynthOptions o;
  o.kinds = {FigureKind::kQuadruped};
  o.poses = 1;
  o.nonisometric = 0.15;
  o.seed = 1;
  return GenerateClass(FigureKind::kQuadruped, o);
}

TEST(SymmetryQuadruped, DefaultsFindTheLeftRightPlaneOfAStretchedQuadruped) {
  const SynthClass cls = StretchedQuadrupeds();
  std::string message;
  const double error = PlaneError(cls, 0, "{type: plane2d}", &message);
  // About 0.05 for the left-right plane, above 1 for a plane perpendicular to it.
  EXPECT_LT(error, 0.2) << message;
}

// The failure mode itself: with the spectral check applied only below a consistency of 0.4, the
// distances' choice (a plane perpendicular to the left-right one) stands.
TEST(SymmetryQuadruped, DistancesAloneChooseAWrongPlaneThere) {
  const SynthClass cls = StretchedQuadrupeds();
  std::string message;
  const double error =
      PlaneError(cls, 0, "{type: plane2d, spectral_min_consistency: 0.4}", &message);
  EXPECT_GT(error, 0.5) << message;
}

}  // namespace
}  // namespace symembed

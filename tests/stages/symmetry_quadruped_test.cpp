// The symmetry stage's defaults on a quadruped whose geodesic distances favour a wrong plane.
//
// A non-isometric quadruped (bones stretched and thickened per pose) has, besides its left-right
// symmetry, an approximate front-back one (front legs to hind legs) and a near-identity one
// (back to belly across the thin body), and its distances and its 2D embedding can prefer either
// of them. The low Laplace-Beltrami eigenfunctions still tell the left-right symmetry apart: this
// is the failure the spectral check must catch by default, whatever the check's threshold would
// have said of the plane chosen by distances.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "core/canonical_frame.h"
#include "eval/synthetic/synthetic.h"
#include "registry/config.h"
#include "registry/registry.h"
#include "registry/shape_pipeline.h"

namespace symembed {
namespace {

template <typename T>
std::unique_ptr<T> Make(const Registry& r, const std::string& kind, const std::string& yaml) {
  return r.CreateAs<T>(kind, YAML::Load(yaml), "test.yaml", "pipeline." + kind);
}

// SymmetryGroundTruthError of the canonical embedding of pose `pose` of the class, the stages
// from sampling to symmetrize at their defaults but for the symmetry stage's `symmetry` YAML.
double PlaneError(const SynthClass& cls, int pose, const std::string& symmetry,
                  std::string* message) {
  Registry r;
  RegisterBuiltinStages(r);
  const TrackedSurface& shape = cls.shapes[pose].shape;
  const auto sampling = Make<SamplingStage>(r, "sampling", "{type: farthest_point}");
  const auto geodesics = Make<GeodesicsStage>(r, "geodesics", "{type: dijkstra}");
  const auto embedding = Make<EmbeddingStage>(r, "embedding", "{type: lsmds}");
  const auto detect = Make<SymmetryStage>(r, "symmetry", symmetry);
  const auto symmetrize = Make<SymmetrizeStage>(r, "symmetrize", "{type: ceres}");
  const std::vector<int> samples = sampling->Run(shape.surface).samples;
  const Eigen::MatrixXd D = geodesics->Prepare(shape.surface)->Distances(samples);
  const EmbeddingResult e = embedding->Run(EmbeddingInput{shape.surface, samples, D});
  const SymmetryInput input{shape.surface, samples, D, e};
  const SymmetryResult s = detect->Run(input);
  *message = s.status.message;
  const Eigen::MatrixX3d Y = CanonicalFrame(symmetrize->Run(input, s).Y);

  std::vector<int> of_rest(cls.rest.surface.NumVertices(), -1);
  for (size_t v = 0; v < shape.rest_ids.size(); ++v) of_rest[shape.rest_ids[v]] = static_cast<int>(v);
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

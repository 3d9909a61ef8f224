// The embedding stages on TOSCA shapes (label `tosca`; skipped without the data): LS-MDS from
// the input coordinates is not reflected, and the reported reflection of every stage is the
// sign of the Procrustes fit computed here independently.
#include <gtest/gtest.h>

#include <Eigen/LU>

#include "core/mesh_io.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// sign det(Xc^T Yc): the sign of the optimal orthogonal Procrustes fit, without an SVD.
int DetSign(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y) {
  const Eigen::MatrixXd Xc = X.rowwise() - X.colwise().mean();
  const Eigen::MatrixXd Yc = Y.rowwise() - Y.colwise().mean();
  return (Xc.transpose() * Yc).determinant() < 0 ? -1 : 1;
}

TEST(EmbeddingTosca, LsmdsKeepsOrientationAndReflectionIsReportedTruthfully) {
  const std::string root = testing::DataRoot();
  if (root.empty()) GTEST_SKIP() << "no data root (set SYMEMBED_DATA)";
  Registry registry;
  RegisterBuiltinStages(registry);
  auto make = [&](const std::string& kind, const std::string& yaml) {
    return registry.Create(kind, YAML::Load(yaml), "test", kind);
  };
  auto preprocess = registry.CreateAs<PreprocessStage>("preprocess", YAML::Load("{}"), "test",
                                                       "preprocess", "standard");
  auto sampling = registry.CreateAs<SamplingStage>(
      "sampling", YAML::Load("{type: farthest_point, count: 500}"), "test", "sampling");
  auto geodesics = registry.CreateAs<GeodesicsStage>("geodesics", YAML::Load("{type: dijkstra}"),
                                                     "test", "geodesics");
  const std::vector<std::string> variants = {"{type: lsmds}", "{type: lsmds, init: isomap}",
                                             "{type: isomap}"};
  std::vector<std::unique_ptr<Stage>> stages;
  for (const auto& v : variants) stages.push_back(make("embedding", v));
  // One shape per class plus the one with a boundary and an original (not remeshed) wolf.
  for (const std::string name : {"cat0", "centaur0", "david0", "dog0", "horse0", "michael0",
                                 "victoria10", "wolf0"}) {
    SCOPED_TRACE(name);
    const Surface surface =
        preprocess->Run(LoadSurface(root + "/tosca_iso_5k/shapes/" + name + ".off")).surface;
    const std::vector<int> ids = sampling->Run(surface).samples;
    const Eigen::MatrixXd D = geodesics->Prepare(surface)->Distances(ids);
    Eigen::MatrixXd X(ids.size(), 3);
    for (size_t i = 0; i < ids.size(); ++i) X.row(i) = surface.V.row(ids[i]);
    for (size_t k = 0; k < stages.size(); ++k) {
      SCOPED_TRACE(variants[k]);
      const auto* stage = dynamic_cast<const EmbeddingStage*>(stages[k].get());
      const EmbeddingResult r = stage->Run({surface, ids, D});
      ASSERT_EQ(r.Y.rows(), surface.NumVertices());
      Eigen::MatrixXd Ys(ids.size(), 3);
      for (size_t i = 0; i < ids.size(); ++i) Ys.row(i) = r.Y.row(ids[i]);
      EXPECT_EQ(r.reflection, DetSign(X, Ys));
      // Graph geodesics of a 5k-vertex mesh embed in 3D with a few percent stress; more than
      // 0.15 would mean a failed embedding.
      EXPECT_LT(r.normalized_stress, 0.15);
      if (k == 0) {
        EXPECT_EQ(r.reflection, 1);
        EXPECT_TRUE(r.status.converged) << r.status.message;
      }
    }
  }
}

}  // namespace
}  // namespace symembed

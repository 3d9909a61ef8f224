// The registered `lsmds` and `isomap` stages on meshes with exactly Euclidean distances.
#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "core/primitives.h"
#include "core/procrustes.h"
#include "registry/registry.h"
#include "stages/embedding/isomap.h"
#include "stages/embedding/lsmds.h"
#include "tests/stages/embedding_test_util.h"

namespace symembed {
namespace {

using testing::CrossCovarianceDetSign;
using testing::EuclideanDistances;

// An ellipsoid (642 vertices) with distinct axes, so the embedding's axes are well defined.
Surface Ellipsoid() {
  Surface s = Icosphere(3);
  s.V = s.V * Eigen::Vector3d(1.0, 0.6, 0.35).asDiagonal();
  return s;
}

Surface Mirrored(const Surface& s) {
  Surface m = s;
  m.V.col(0) *= -1.0;
  m.F.col(1).swap(m.F.col(2));
  return m;
}

std::vector<int> EveryThird(int n) {
  std::vector<int> samples;
  for (int v = 0; v < n; v += 3) samples.push_back(v);
  return samples;
}

Eigen::MatrixXd Rows(const Eigen::MatrixXd& M, const std::vector<int>& ids) {
  Eigen::MatrixXd R(ids.size(), M.cols());
  for (size_t i = 0; i < ids.size(); ++i) R.row(i) = M.row(ids[i]);
  return R;
}

std::unique_ptr<EmbeddingStage> Make(const std::string& yaml) {
  Registry registry;
  RegisterBuiltinStages(registry);
  return registry.CreateAs<EmbeddingStage>("embedding", YAML::Load(yaml), "test.yaml",
                                           "pipeline.embedding");
}

// Rigid Procrustes residual of Y against V relative to the RMS radius of V.
double RelativeResidual(const Eigen::MatrixXd& V, const Eigen::MatrixXd& Y) {
  const Eigen::MatrixXd Vc = V.rowwise() - V.colwise().mean();
  return FitProcrustes(V, Y).rms_residual / std::sqrt(Vc.squaredNorm() / V.rows());
}

TEST(LsmdsStage, EuclideanDistancesGiveTheSurfaceBackUnreflected) {
  const auto stage = Make("{type: lsmds}");
  for (const Surface& s : {Ellipsoid(), Mirrored(Ellipsoid())}) {
    const std::vector<int> samples = EveryThird(s.NumVertices());
    const Eigen::MatrixXd D = EuclideanDistances(Rows(s.V, samples), s.V);
    const EmbeddingResult r = stage->Run({s, samples, D});
    ASSERT_EQ(r.Y.rows(), s.NumVertices());
    ASSERT_EQ(r.Y.cols(), 3);
    EXPECT_TRUE(r.status.converged);
    EXPECT_LT(r.normalized_stress, 1e-9);  // exact distances, exact start: rounding only
    EXPECT_EQ(r.reflection, 1);
    EXPECT_EQ(CrossCovarianceDetSign(Rows(s.V, samples), Rows(r.Y, samples)), 1);
    EXPECT_FALSE(r.stress_history.empty());
    // Out-of-sample vertices too: exact distances to 12 samples pin each one down, and
    // Gauss-Newton converges quadratically on exact data, so only rounding is left.
    EXPECT_LT(RelativeResidual(s.V, r.Y), 1e-9);
  }
}

TEST(IsomapStage, ReportsReflectionAndFixesItOnRequest) {
  const auto plain = Make("{type: isomap}");
  const auto fixed = Make("{type: isomap, fix_orientation: true}");
  // The surface and its mirror image have identical distances, hence identical classical MDS
  // embeddings, so exactly one of the two is reflected relative to its input.
  std::vector<int> reflections;
  for (const Surface& s : {Ellipsoid(), Mirrored(Ellipsoid())}) {
    const std::vector<int> samples = EveryThird(s.NumVertices());
    const Eigen::MatrixXd D = EuclideanDistances(Rows(s.V, samples), s.V);
    const EmbeddingResult r = plain->Run({s, samples, D});
    EXPECT_LT(r.normalized_stress, 1e-8);         // Euclidean input: classical MDS is exact
    EXPECT_LT(RelativeResidual(s.V, r.Y), 1e-8);  // landmark MDS is exact for Euclidean data
    EXPECT_EQ(r.reflection, CrossCovarianceDetSign(Rows(s.V, samples), Rows(r.Y, samples)));
    reflections.push_back(r.reflection);
    const EmbeddingResult f = fixed->Run({s, samples, D});
    EXPECT_EQ(f.reflection, 1);
    EXPECT_EQ(CrossCovarianceDetSign(Rows(s.V, samples), Rows(f.Y, samples)), 1);
    EXPECT_LT(RelativeResidual(s.V, f.Y), 1e-8);
  }
  EXPECT_EQ(reflections[0], -reflections[1]);
}

// The embedding functions take any dimension (the stages only 3, which the pipeline needs).
TEST(EmbeddingStages, TwoDimensionsReportNoReflection) {
  const Surface s = Ellipsoid();
  const std::vector<int> samples = EveryThird(s.NumVertices());
  const Eigen::MatrixXd D = EuclideanDistances(Rows(s.V, samples), s.V);
  for (const std::string type : {"lsmds", "isomap"}) {
    for (const std::string init : {"original", "isomap", "random"}) {
      if (type == "isomap" && init != "original") continue;
      SCOPED_TRACE(type + " " + init);
      LsmdsOptions lsmds;
      lsmds.dims = 2;
      lsmds.init = init == "original" ? LsmdsInit::kOriginal
                   : init == "isomap" ? LsmdsInit::kIsomap
                                      : LsmdsInit::kRandom;
      IsomapOptions isomap;
      isomap.dims = 2;
      const EmbeddingResult r = type == "lsmds" ? LsmdsEmbedding({s, samples, D}, lsmds)
                                                : IsomapEmbedding({s, samples, D}, isomap);
      EXPECT_EQ(r.Y.cols(), 2);
      EXPECT_EQ(r.reflection, 1);
      // A 3D ellipsoid squeezed into 2D keeps a visible stress (the 0.35 axis is lost).
      EXPECT_GT(r.normalized_stress, 0.01);
      EXPECT_LT(r.normalized_stress, 0.5);
    }
  }
}

TEST(LsmdsStage, InitsReachLowStressOnEuclideanDistances) {
  const Surface s = Ellipsoid();
  const std::vector<int> samples = EveryThird(s.NumVertices());
  const Eigen::MatrixXd D = EuclideanDistances(Rows(s.V, samples), s.V);
  for (const std::string init : {"isomap", "random"}) {
    const EmbeddingResult r =
        Make("{type: lsmds, init: " + init + ", seed: 3, tolerance: 1e-9}")->Run({s, samples, D});
    // Isomap's start is already exact; from random, SMACOF on exact 3D data finds the global
    // minimum on this convex shape (1e-3 leaves room for slow final convergence).
    EXPECT_LT(r.normalized_stress, 1e-3) << init;
    EXPECT_EQ(r.reflection, CrossCovarianceDetSign(Rows(s.V, samples), Rows(r.Y, samples)));
  }
}

TEST(EmbeddingStages, ResolvedOptionsAndStrictParsing) {
  const auto lsmds = Make("{type: lsmds}");
  const YAML::Node& o = lsmds->resolved_options();
  EXPECT_EQ(o["dims"].as<int>(), 3);
  EXPECT_EQ(o["init"].as<std::string>(), "original");
  EXPECT_DOUBLE_EQ(o["tolerance"].as<double>(), 1e-6);
  EXPECT_EQ(Make("{type: isomap}")->resolved_options()["fix_orientation"].as<bool>(), false);
  EXPECT_THROW(Make("{type: lsmds, dims: 4}"), ConfigError);
  EXPECT_THROW(Make("{type: lsmds, init: pca}"), ConfigError);
  EXPECT_THROW(Make("{type: lsmds, relaxation: 2.5}"), ConfigError);
  EXPECT_THROW(Make("{type: isomap, init: original}"), ConfigError);
  try {
    Make("{type: lsmds, init: pca}");
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("original"), std::string::npos) << e.what();
  }
}

TEST(EmbeddingStages, RejectBadInput) {
  const Surface s = Ellipsoid();
  std::vector<int> samples = EveryThird(s.NumVertices());
  const Eigen::MatrixXd D = EuclideanDistances(Rows(s.V, samples), s.V);
  for (const std::string type : {"lsmds", "isomap"}) {
    const auto stage = Make("{type: " + type + "}");
    const Eigen::MatrixXd short_d = D.leftCols(10);
    EXPECT_THROW(stage->Run({s, samples, short_d}), InvalidInputError);
    std::vector<int> duplicate = samples;
    duplicate[1] = duplicate[0];
    EXPECT_THROW(stage->Run({s, duplicate, D}), InvalidInputError);
    Eigen::MatrixXd infinite = D;
    infinite(0, 5) = std::numeric_limits<double>::infinity();
    EXPECT_THROW(stage->Run({s, samples, infinite}), InvalidInputError);
  }
}

}  // namespace
}  // namespace symembed

#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include "core/errors.h"
#include "core/laplacian.h"
#include "core/matching/deformed.h"
#include "core/matching/nearest.h"
#include "core/primitives.h"
#include "core/spectral.h"
#include "registry/product_needs.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// The figure's vertices shuffled: perm[i] is the new index of vertex i.
Eigen::MatrixX3d Shuffled(const Eigen::MatrixX3d& V, std::vector<int>* perm) {
  perm->resize(V.rows());
  std::iota(perm->begin(), perm->end(), 0);
  std::shuffle(perm->begin(), perm->end(), std::mt19937(3));
  Eigen::MatrixX3d out(V.rows(), 3);
  for (int i = 0; i < V.rows(); ++i) out.row((*perm)[i]) = V.row(i);
  return out;
}

TEST(NearestMatching, RecoversAPermutation) {
  const Surface figure = testing::SymmetricFigure();
  std::vector<int> perm;
  const Eigen::MatrixX3d target = Shuffled(figure.V, &perm);
  const MatchResult r = MatchNearest(figure.V, target, 2);
  EXPECT_EQ(r.map, perm);
  EXPECT_EQ(r.status.residual, 0.0);
}

TEST(NearestScaledMatching, AbsorbsPerAxisScaleAndTranslation) {
  const Surface figure = testing::SymmetricFigure();
  std::vector<int> perm;
  Eigen::MatrixX3d target = Shuffled(figure.V, &perm);
  const Eigen::RowVector3d scale(1.15, 0.9, 1.1), shift(0.05, -0.03, 0.02);
  target = (target.array().rowwise() * scale.array()).rowwise() + shift.array();
  ScaledAlignment a;
  ScaledIcpOptions options;
  options.normal_weight = 0.0;  // positions only: the figure's points without normals
  const MatchResult r = MatchNearestScaled({figure.V, {}}, {target, {}}, options, &a);
  int correct = 0;
  for (size_t i = 0; i < perm.size(); ++i) correct += r.map[i] == perm[i];
  // ICP converges to the exact alignment of this figure (checked: all vertices).
  EXPECT_EQ(correct, static_cast<int>(perm.size()));
  EXPECT_NEAR((a.scale.transpose() - scale).norm(), 0.0, 1e-6);
  EXPECT_NEAR((a.translation.transpose() - shift).norm(), 0.0, 1e-6);
  // Plain nearest gets many wrong on the stretched target.
  const MatchResult plain = MatchNearest(figure.V, target, 1);
  int plain_correct = 0;
  for (size_t i = 0; i < perm.size(); ++i) plain_correct += plain.map[i] == perm[i];
  EXPECT_LT(plain_correct, correct);
}

// A thin slab (a sphere flattened to thickness t) against the same slab raised by 0.8 t: the
// nearest target point of every source point on the upper side is on the target's lower side,
// 0.2 t away, while its own image is 0.8 t away. Normals of opposite sides differ by 2, so with
// (w r)^2 * 4 > 0.8^2 - 0.2^2 the sides are kept.
TEST(NearestMatching, NormalsKeepTheSidesOfAThinPart) {
  Surface slab = Icosphere(3);
  const double t = 0.1;
  slab.V.col(2) *= t / 2.0;
  const Eigen::MatrixX3d N = VertexNormals(slab);
  Eigen::MatrixX3d raised = slab.V;
  raised.col(2).array() += 0.8 * t;
  const EmbeddedPoints source{slab.V, N}, target{raised, N};
  auto side_errors = [&](const MatchResult& r) {
    int wrong = 0;
    for (int i = 0; i < slab.NumVertices(); ++i) {
      if (std::abs(slab.V(i, 2)) > 0.25 * t && slab.V(i, 2) * slab.V(r.map[i], 2) < 0.0) ++wrong;
    }
    return wrong;
  };
  const MatchResult plain = MatchNearest(source, target, 0.0, 1);
  EXPECT_GT(side_errors(plain), slab.NumVertices() / 4);
  // r = RMS radius of the raised slab (about 0.82); w r = 0.1 * 0.82 > sqrt(0.6) t / 2.
  const MatchResult with_normals = MatchNearest(source, target, 0.1, 1);
  EXPECT_EQ(side_errors(with_normals), 0);
  // Without normals where they are needed: a clear error naming the side.
  try {
    MatchNearest({slab.V, {}}, target, 0.1, 1);
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("source normals"), std::string::npos) << e.what();
  }
  EXPECT_THROW(MatchNearest(source, target, -1.0, 1), ConfigError);
}

// The pose difference the embeddings of two poses keep: the figure with its arms held out
// against the same figure with the arms lowered and the legs spread (vertex ids unchanged, so
// the truth is the identity). Nearest neighbours send the ends of the arms elsewhere; the
// deformation smooth along the source follows the limbs.
TEST(DeformedMatching, FollowsAPoseChangeThatNearestMisses) {
  const Surface source = testing::SymmetricFigure(2);
  const Surface target = testing::PosedSymmetricFigure(2, 0.6, 0.25);
  const EmbeddedPoints s{source.V, VertexNormals(source)}, t{target.V, VertexNormals(target)};
  LaplaceBasisOptions basis_options;
  basis_options.k = 30;
  const LaplaceBasis basis = ComputeLaplaceBasis(source, basis_options);
  std::vector<int> samples_s, samples_t;
  for (int i = 0; i < source.NumVertices(); i += 2) samples_s.push_back(i);
  for (int i = 1; i < target.NumVertices(); i += 2) samples_t.push_back(i);
  auto mean_error = [&](const MatchResult& r) {
    double sum = 0.0;
    for (int i = 0; i < source.NumVertices(); ++i) sum += (target.V.row(r.map[i]) - target.V.row(i)).norm();
    return sum / source.NumVertices();
  };
  DeformOptions options;
  options.k_end = 30;
  const DeformResult d = DeformSource(s, source.F, basis, samples_s, t, samples_t, options);
  EXPECT_LT(d.residual_after, 0.25 * d.residual_before);
  const double nearest = mean_error(MatchNearest(s, t, options.normal_weight, 1));
  const double deformed =
      mean_error(MatchNearest({d.Y, d.N}, t, options.normal_weight, 1));
  EXPECT_LT(deformed, 0.5 * nearest) << "nearest " << nearest << ", deformed " << deformed;
  EXPECT_TRUE(d.N.isApprox(VertexNormals(d.Y, source.F)));  // the moved surface's normals

  // More smoothness moves the source less.
  options.smoothness = 10.0;
  const DeformResult stiff = DeformSource(s, source.F, basis, samples_s, t, samples_t, options);
  EXPECT_GT(stiff.residual_after, d.residual_after);

  options.k_end = 31;  // more than the basis holds
  EXPECT_THROW(DeformSource(s, source.F, basis, samples_s, t, samples_t, options),
               InvalidInputError);
  options.k_end = 30;
  options.smoothness = -1.0;
  EXPECT_THROW(DeformSource(s, source.F, basis, samples_s, t, samples_t, options), ConfigError);
}

// The registered stage reads the source's basis (its declared need) and samples from the pair.
TEST(DeformedMatching, RegisteredStageAlignsThroughThePair) {
  Registry registry;
  RegisterBuiltinStages(registry);
  auto stage = registry.CreateAs<MatchingStage>(
      "matching", YAML::Load("{type: deformed, k_end: 24, samples: 400}"), "t.yaml",
      "pipeline.matching");
  EXPECT_EQ(stage->Needs().basis, 24);
  ShapeData source, target;
  source.name = "source";
  target.name = "target";
  source.surface = testing::SymmetricFigure(2);
  target.surface = testing::PosedSymmetricFigure(2, 0.6, 0.25);
  for (ShapeData* shape : {&source, &target}) {
    shape->Y = shape->surface.V;
    for (int i = 0; i < shape->surface.NumVertices(); i += 3) shape->samples.push_back(i);
    ComputeNeeds(stage->Needs(), shape);
  }
  const PairInput pair{source, target};
  const EmbeddedPoints s{source.Y, VertexNormals(source.surface)};
  const EmbeddedPoints t{target.Y, VertexNormals(target.surface)};
  EmbeddedPoints moved;
  ASSERT_TRUE(stage->Align(pair, s, t, &moved));
  ASSERT_EQ(moved.Y.rows(), s.Y.rows());
  ASSERT_EQ(moved.N.rows(), s.Y.rows());
  auto correct = [&](const MatchResult& r) {
    int n = 0;
    for (int i = 0; i < source.surface.NumVertices(); ++i) {
      n += (target.surface.V.row(r.map[i]) - target.surface.V.row(i)).norm() < 0.1;
    }
    return n;
  };
  EXPECT_GT(correct(stage->Run(moved, t)), correct(stage->Run(s, t)));
  // Without the basis it needs, the error names the shape.
  ShapeData bare = source;
  bare.basis = LaplaceBasis{};
  try {
    stage->Align(PairInput{bare, target}, s, t, &moved);
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("source"), std::string::npos) << e.what();
  }
}

TEST(Matching, RegisteredStagesRun) {
  Registry registry;
  RegisterBuiltinStages(registry);
  const Surface figure = testing::SymmetricFigure();
  for (const std::string& name : registry.Names("matching")) {
    auto stage = registry.CreateAs<MatchingStage>("matching", YAML::Load("{type: " + name + "}"),
                                                  "t.yaml", "pipeline.matching");
    const EmbeddedPoints points{figure.V, VertexNormals(figure)};
    const MatchResult r = stage->Run(points, points);
    std::vector<int> identity(figure.NumVertices());
    std::iota(identity.begin(), identity.end(), 0);
    EXPECT_EQ(r.map, identity) << name;
  }
}

}  // namespace
}  // namespace symembed

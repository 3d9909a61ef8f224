#include <gtest/gtest.h>

#include <numeric>
#include <random>

#include "registry/registry.h"
#include "stages/matching/nearest.h"
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
  const MatchResult r = MatchNearestScaled(figure.V, target, ScaledIcpOptions{}, &a);
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

TEST(Matching, RegisteredStagesRun) {
  Registry registry;
  RegisterBuiltinStages(registry);
  const Surface figure = testing::SymmetricFigure();
  for (const std::string& name : registry.Names("matching")) {
    auto stage = registry.CreateAs<MatchingStage>("matching", YAML::Load("{type: " + name + "}"),
                                                  "t.yaml", "pipeline.matching");
    const MatchResult r = stage->Run(figure.V, figure.V);
    std::vector<int> identity(figure.NumVertices());
    std::iota(identity.begin(), identity.end(), 0);
    EXPECT_EQ(r.map, identity) << name;
  }
}

}  // namespace
}  // namespace symembed

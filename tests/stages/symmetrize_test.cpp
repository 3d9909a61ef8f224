#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "core/knn.h"
#include "core/procrustes.h"
#include "registry/registry.h"
#include "stages/symmetrize/ceres_symmetrize.h"
#include "stages/symmetrize/simple_symmetrize.h"
#include "stages/symmetrize/stress_majorization.h"
#include "stages/symmetrize/symmetrize_common.h"
#include "stages/symmetrize/symmetrize_costs.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

const Eigen::Matrix3d kRotation =
    Eigen::AngleAxisd(0.9, Eigen::Vector3d(1.0, 2.0, -0.5).normalized()).toRotationMatrix();
const Eigen::RowVector3d kShift(0.3, -1.2, 2.0);

// Residual of each cost through a plain functor, differentiated numerically by Ceres.
struct EdgeStressFunctor {
  double d0, inv_scale;
  bool operator()(const double* a, const double* b, double* r) const {
    r[0] = (std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) +
                      (a[2] - b[2]) * (a[2] - b[2])) - d0) * inv_scale;
    return true;
  }
};
struct LinearFunctor {
  std::vector<Eigen::Matrix3d> A;
  double w;
  bool operator()(double const* const* x, double* r) const {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (size_t b = 0; b < A.size(); ++b) sum += A[b] * Eigen::Map<const Eigen::Vector3d>(x[b]);
    for (int c = 0; c < 3; ++c) r[c] = w * sum(c);
    return true;
  }
};
struct OnPlaneFunctor {
  double w;
  bool operator()(const double* a, double* r) const {
    r[0] = w * a[0];
    return true;
  }
};

// Evaluates residuals and Jacobians of two cost functions at the same point and compares them.
void ExpectSameJacobians(const ceres::CostFunction& analytic, const ceres::CostFunction& numeric,
                         const std::vector<const double*>& params) {
  const int m = analytic.num_residuals();
  ASSERT_EQ(m, numeric.num_residuals());
  const auto& sizes = analytic.parameter_block_sizes();
  std::vector<std::vector<double>> ja(sizes.size()), jn(sizes.size());
  std::vector<double*> pa, pn;
  for (size_t b = 0; b < sizes.size(); ++b) {
    ja[b].assign(m * sizes[b], 0.0);
    jn[b].assign(m * sizes[b], 0.0);
    pa.push_back(ja[b].data());
    pn.push_back(jn[b].data());
  }
  std::vector<double> ra(m), rn(m);
  ASSERT_TRUE(analytic.Evaluate(params.data(), ra.data(), pa.data()));
  ASSERT_TRUE(numeric.Evaluate(params.data(), rn.data(), pn.data()));
  for (int i = 0; i < m; ++i) EXPECT_NEAR(ra[i], rn[i], 1e-14);
  for (size_t b = 0; b < sizes.size(); ++b) {
    for (size_t k = 0; k < ja[b].size(); ++k) {
      // Central differences on O(1) inputs: error ~1e-9 or better.
      EXPECT_NEAR(ja[b][k], jn[b][k], 1e-7) << "block " << b << " entry " << k;
    }
  }
}

TEST(CeresSymmetrize, ResidualJacobiansMatchNumericDifferentiation) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    double a[3], b[3];
    for (int c = 0; c < 3; ++c) {
      a[c] = u(rng);
      b[c] = u(rng);
    }
    const double d0 = 0.5 + 0.5 * u(rng), inv_scale = 1.7, w = 2.3;
    ExpectSameJacobians(
        EdgeStressCost(d0, inv_scale),
        ceres::NumericDiffCostFunction<EdgeStressFunctor, ceres::CENTRAL, 1, 3, 3>(
            new EdgeStressFunctor{d0, inv_scale}),
        {a, b});
    // The symmetry residual M a - 0.7 b - 0.3 c with random blocks.
    double c3[3] = {u(rng), u(rng), u(rng)};
    const std::vector<Eigen::Matrix3d> A = {MirrorX(), -0.7 * Eigen::Matrix3d::Identity(),
                                            -0.3 * Eigen::Matrix3d::Identity()};
    ceres::DynamicNumericDiffCostFunction<LinearFunctor, ceres::CENTRAL> numeric(
        new LinearFunctor{A, w});
    for (int b = 0; b < 3; ++b) numeric.AddParameterBlock(3);
    numeric.SetNumResiduals(3);
    ExpectSameJacobians(LinearResidualCost(A, w), numeric, {a, b, c3});
    ExpectSameJacobians(OnPlaneCost(w),
                        ceres::NumericDiffCostFunction<OnPlaneFunctor, ceres::CENTRAL, 1, 3>(
                            new OnPlaneFunctor{w}),
                        {a});
  }
}

// The figure with its left side (x < 0) deformed smoothly: stretched along y by 8% and bent, so
// it is no longer symmetric; sigma stays the mirror map of the undeformed figure.
struct AsymmetricFigure {
  Surface surface;
  std::vector<int> sigma;
  Eigen::MatrixXd Y;  // deformed, then moved rigidly
  SymmetryResult symmetry;
};

AsymmetricFigure MakeAsymmetricFigure() {
  AsymmetricFigure f;
  f.surface = testing::SymmetricFigure(1, true, &f.sigma);
  Eigen::MatrixX3d V = f.surface.V;
  for (int i = 0; i < V.rows(); ++i) {
    const double x = V(i, 0);
    if (x < 0.0) {
      V(i, 1) *= 1.0 + 0.08 * std::min(1.0, -x / 0.3);
      V(i, 2) += 0.05 * x * x;
    }
  }
  f.Y = (V * kRotation.transpose()).rowwise() + kShift;
  f.symmetry.normal = kRotation.col(0);
  f.symmetry.offset = kRotation.col(0).dot(kShift.transpose());
  f.symmetry.sigma = f.sigma;
  f.symmetry.confidence = Eigen::VectorXd::Ones(V.rows());
  return f;
}

std::vector<int> AllVertices(int n) {
  std::vector<int> ids(n);
  for (int i = 0; i < n; ++i) ids[i] = i;
  return ids;
}

TEST(CeresSymmetrize, LowersAsymmetryAndKeepsStress) {
  const AsymmetricFigure f = MakeAsymmetricFigure();
  const std::vector<int> samples = AllVertices(f.surface.NumVertices());
  CeresSymmetrizeOptions options;
  options.symmetry_weight = 10.0;
  const SymmetrizeResult r = SymmetrizeCeres(f.Y, samples, f.symmetry, options);
  EXPECT_GT(r.asymmetry_before, 0.01);  // the deformation is visible
  // symmetry_weight 10 against the stress: the residual asymmetry is a small fraction.
  EXPECT_LT(r.asymmetry_after, 0.1 * r.asymmetry_before);
  const Eigen::MatrixX3d before = MovePlaneToX0(f.Y, f.symmetry.normal, f.symmetry.offset);
  // The deformation halves the 8% stretch on each side: edge lengths change by a few percent.
  EXPECT_LT(GraphStress(before, r.Y, 10), 0.05);
  EXPECT_TRUE(r.status.converged) << r.status.message;
}

// Every third vertex as a sample and sigma from geometry (the nearest mirrored sample), as the
// symmetry stages produce it: the samples are not placed symmetrically and sigma is not a
// bijection.
TEST(CeresSymmetrize, CombinedMirrorCounterpartsKeepTheShapeUnderCoarseSampling) {
  const AsymmetricFigure f = MakeAsymmetricFigure();
  std::vector<int> samples;
  for (int i = 0; i < f.surface.NumVertices(); i += 3) samples.push_back(i);
  SymmetryResult sym = f.symmetry;
  const Eigen::MatrixX3d before = MovePlaneToX0(f.Y, sym.normal, sym.offset);
  Eigen::MatrixX3d P(samples.size(), 3);
  for (size_t i = 0; i < samples.size(); ++i) P.row(i) = before.row(samples[i]);
  Eigen::MatrixX3d Q = P;
  Q.col(0) *= -1.0;
  sym.sigma = KnnIndex(P).Nearest(Q, nullptr, 1);
  sym.confidence = Eigen::VectorXd::Ones(samples.size());

  CeresSymmetrizeOptions combined;
  combined.mirror_neighbors = 4;
  combined.symmetry_weight = 10.0;
  const SymmetrizeResult soft = SymmetrizeCeres(f.Y, samples, sym, combined);
  ASSERT_EQ(soft.Y.rows(), f.surface.NumVertices());
  Eigen::MatrixX3d X(samples.size(), 3);
  for (size_t i = 0; i < samples.size(); ++i) X.row(i) = soft.Y.row(samples[i]);
  const auto weights = MirrorWeights(P, sym.sigma, 4);
  // The reflected samples come closer to their counterparts...
  EXPECT_LT(MirrorResidual(X, weights), 0.7 * MirrorResidual(P, weights));
  // ...while the shape is kept (measured on every vertex: dense vertices followed).
  EXPECT_LT(GraphStress(before, soft.Y, 10), 0.05);
  // One mirror sample per sample instead: many samples share a mirror sample and are pulled
  // together, which costs far more stress.
  CeresSymmetrizeOptions hard;
  hard.symmetry_weight = 10.0;
  const SymmetrizeResult r = SymmetrizeCeres(f.Y, samples, sym, hard);
  EXPECT_GT(GraphStress(before, r.Y, 10), 2.0 * GraphStress(before, soft.Y, 10));
}

TEST(StressMajorization, NeverRaisesTheEnergyAndApproachesTheCeresMinimum) {
  const AsymmetricFigure f = MakeAsymmetricFigure();
  const Eigen::MatrixX3d P = MovePlaneToX0(f.Y, f.symmetry.normal, f.symmetry.offset);
  CeresSymmetrizeOptions options;
  options.symmetry_weight = 10.0;
  const SymmetrizeEnergy energy = CeresSymmetrizeEnergy(P, f.symmetry, options);
  double previous = energy.Evaluate(P);
  Eigen::MatrixX3d X = P;
  for (int step = 0; step < 20; ++step) {
    const MajorizationResult r = MajorizeSymmetrizeEnergy(energy, X, 1, 0.0);
    EXPECT_EQ(r.iterations, 1);
    EXPECT_LE(r.energy_after, previous * (1.0 + 1e-12)) << "step " << step;
    EXPECT_NEAR(r.energy_after, energy.Evaluate(r.X), 1e-12 * previous);
    previous = r.energy_after;
    X = r.X;
  }
  // Many iterations end near the energy Ceres reaches from the same start (Ceres's cost is
  // half the energy divided by the squared size of the sample set).
  const MajorizationResult many = MajorizeSymmetrizeEnergy(energy, P, 2000, 1e-9);
  EXPECT_LT(many.energy_after, 0.05 * many.energy_before);
  options.warm_start_iterations = 0;  // Ceres alone
  options.max_iterations = 100;
  const std::vector<int> samples = AllVertices(f.surface.NumVertices());
  const SymmetrizeResult ceres = SymmetrizeCeres(f.Y, samples, f.symmetry, options);
  const double ceres_energy = 2.0 * ceres.status.residual * RmsRadius(P) * RmsRadius(P);
  EXPECT_NEAR(many.energy_after, ceres_energy, 0.02 * ceres_energy);
}

TEST(CeresSymmetrize, WarmStartReachesTheSameResult) {
  const AsymmetricFigure f = MakeAsymmetricFigure();
  const std::vector<int> samples = AllVertices(f.surface.NumVertices());
  CeresSymmetrizeOptions cold;
  cold.symmetry_weight = 10.0;
  cold.warm_start_iterations = 0;
  cold.max_iterations = 100;
  CeresSymmetrizeOptions warm = cold;
  warm.warm_start_iterations = 300;
  const SymmetrizeResult a = SymmetrizeCeres(f.Y, samples, f.symmetry, cold);
  const SymmetrizeResult b = SymmetrizeCeres(f.Y, samples, f.symmetry, warm);
  EXPECT_NE(b.status.message.find("majorization iterations"), std::string::npos)
      << b.status.message;
  EXPECT_LE(b.status.iterations, a.status.iterations) << a.status.message << "\n"
                                                      << b.status.message;
  EXPECT_NEAR(b.status.residual, a.status.residual, 1e-3 * a.status.residual);
  // The energy does not change under translations within the plane and rotations about its
  // normal, which the two starts leave differently: compare the shapes by their edge lengths.
  EXPECT_LT(GraphStress(a.Y, b.Y, 10), 1e-3);
}

TEST(CeresSymmetrize, WithoutIterationsTheMajorizationsPositionsWithoutCeres) {
  // max_iterations 0: the samples end where the majorization leaves them, and the
  // residual is Ceres' cost of those positions (half the energy over the squared size); one
  // Levenberg-Marquardt iteration more lowers that cost further.
  const AsymmetricFigure f = MakeAsymmetricFigure();
  const std::vector<int> samples = AllVertices(f.surface.NumVertices());
  CeresSymmetrizeOptions options;
  options.max_iterations = 0;
  const SymmetrizeResult r = SymmetrizeCeres(f.Y, samples, f.symmetry, options);
  const Eigen::MatrixX3d P = MovePlaneToX0(f.Y, f.symmetry.normal, f.symmetry.offset);
  const SymmetrizeEnergy energy = CeresSymmetrizeEnergy(P, f.symmetry, options);
  const MajorizationResult warm = MajorizeSymmetrizeEnergy(energy, P, options.warm_start_iterations,
                                                           options.warm_start_tolerance);
  EXPECT_EQ(r.status.iterations, warm.iterations);
  const double size = RmsRadius(P);
  EXPECT_DOUBLE_EQ(r.status.residual, 0.5 * warm.energy_after / (size * size));
  EXPECT_NE(r.status.message.find("no Levenberg-Marquardt"), std::string::npos) << r.status.message;
  EXPECT_LT(r.asymmetry_after, 0.5 * r.asymmetry_before);
  CeresSymmetrizeOptions polished = options;
  polished.max_iterations = 1;
  const SymmetrizeResult p = SymmetrizeCeres(f.Y, samples, f.symmetry, polished);
  EXPECT_EQ(p.status.message.find("no Levenberg-Marquardt"), std::string::npos);
  EXPECT_LT(p.status.residual, r.status.residual);
}

TEST(AverageSymmetrize, ExactlySymmetricForAnInvolution) {
  const AsymmetricFigure f = MakeAsymmetricFigure();
  const std::vector<int> samples = AllVertices(f.surface.NumVertices());
  const SymmetrizeResult r = SymmetrizeAverage(f.Y, samples, f.symmetry);
  EXPECT_GT(r.asymmetry_before, 0.01);
  EXPECT_LT(r.asymmetry_after, 1e-12);  // rounding only
  EXPECT_LT(Asymmetry(r.Y, f.sigma), 1e-12);
}

TEST(NoneSymmetrize, MovesThePlaneToXZero) {
  std::vector<int> mirror;
  const Surface figure = testing::SymmetricFigure(1, true, &mirror);
  const Eigen::MatrixXd Y = (figure.V * kRotation.transpose()).rowwise() + kShift;
  SymmetryResult sym;
  sym.normal = -2.0 * kRotation.col(0);  // any length and sign
  sym.offset = -2.0 * kRotation.col(0).dot(kShift.transpose());
  sym.sigma = mirror;
  const SymmetrizeResult r = SymmetrizeNone(Y, AllVertices(figure.NumVertices()), sym);
  EXPECT_LT(r.asymmetry_before, 1e-12);
  EXPECT_NEAR(r.Y.col(0).mean(), 0.0, 1e-12);
  // Rigid: pairwise distances unchanged.
  EXPECT_NEAR((r.Y.row(5) - r.Y.row(77)).norm(), (Y.row(5) - Y.row(77)).norm(), 1e-12);
}

TEST(Symmetrize, RegisteredStagesRun) {
  Registry registry;
  RegisterBuiltinStages(registry);
  const AsymmetricFigure f = MakeAsymmetricFigure();
  const std::vector<int> samples = AllVertices(f.surface.NumVertices());
  EmbeddingResult embedding;
  embedding.Y = f.Y;
  const Eigen::MatrixXd D;  // unused by the symmetrize stages
  const SymmetryInput input{f.surface, samples, D, embedding};
  for (const std::string& name : registry.Names("symmetrize")) {
    auto stage = registry.CreateAs<SymmetrizeStage>("symmetrize", YAML::Load("{type: " + name + "}"),
                                                    "t.yaml", "pipeline.symmetrize");
    const SymmetrizeResult r = stage->Run(input, f.symmetry);
    EXPECT_EQ(r.Y.rows(), f.surface.NumVertices()) << name;
    EXPECT_LE(r.asymmetry_after, r.asymmetry_before + 1e-12) << name;
  }
}

}  // namespace
}  // namespace symembed

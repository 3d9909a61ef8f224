// The embedding algorithms on point sets with exactly Euclidean distances (no geodesics).
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "core/errors.h"
#include "core/mds/classical_mds.h"
#include "core/mds/smacof.h"
#include "core/procrustes.h"
#include "stages/embedding/out_of_sample.h"
#include "tests/stages/embedding_test_util.h"

namespace symembed {
namespace {

using testing::BoxPoints;
using testing::EuclideanDistances;

// Rigid (orthogonal, no scale) Procrustes residual of Y against the truth P, relative to P's
// RMS radius.
double RelativeResidual(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Y) {
  const Eigen::MatrixXd Pc = P.rowwise() - P.colwise().mean();
  const double radius = std::sqrt(Pc.squaredNorm() / P.rows());
  return FitProcrustes(P, Y).rms_residual / radius;
}

Eigen::MatrixXd RandomConfiguration(int n, int dims, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixXd X(n, dims);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < dims; ++c) X(i, c) = normal(rng);
  return X;
}

// Distances that are not Euclidean in any dimension: Euclidean ones stretched by a smooth
// factor (as geodesics on a curved surface exceed chords).
Eigen::MatrixXd CurvedDistances(const Eigen::MatrixXd& P) {
  Eigen::MatrixXd D = EuclideanDistances(P, P);
  return (D.array() * (1.0 + 0.3 * D.array().square())).matrix();
}

TEST(Smacof, OriginalInitOnEuclideanPointsHasZeroStressAndNoReflection) {
  const Eigen::MatrixXd P = BoxPoints(150, 1);
  const Eigen::MatrixXd D = EuclideanDistances(P, P);
  // Start from the coordinates in other units (x 7.5 and shifted), as surface coordinates are.
  const Eigen::MatrixXd start = ((7.5 * P).rowwise() + Eigen::RowVector3d(1, 2, 3)).eval();
  const SmacofResult r = Smacof(D, ScaleToDistances(D, start));
  EXPECT_TRUE(r.converged);
  // Exact distances and the least-squares scale reproduce them: stress is rounding only.
  EXPECT_LT(r.normalized_stress, 1e-9);
  EXPECT_LT(RelativeResidual(P, r.X), 1e-9);
  EXPECT_EQ(ProcrustesReflection(P, r.X), 1);
}

TEST(Smacof, RecoversEuclideanPointsFromPerturbedStart) {
  const Eigen::MatrixXd P = BoxPoints(120, 2);
  const Eigen::MatrixXd D = EuclideanDistances(P, P);
  const Eigen::MatrixXd start = P + 0.05 * RandomConfiguration(120, 3, 7);
  SmacofOptions options;
  options.tolerance = 1e-12;
  options.max_iterations = 5000;
  const SmacofResult r = Smacof(D, start, options);
  // Converges linearly to the exact configuration; 1e-5 of the radius is far below any
  // perturbation left from the start (5% of unit noise) and well above rounding.
  EXPECT_LT(r.normalized_stress, 1e-5);
  EXPECT_LT(RelativeResidual(P, r.X), 1e-5);
  EXPECT_EQ(ProcrustesReflection(P, r.X), 1);
}

TEST(Smacof, StressNeverIncreasesAndHistoryIsTheIteratesStress) {
  const Eigen::MatrixXd P = BoxPoints(60, 3);
  const Eigen::MatrixXd D = CurvedDistances(P);
  for (int anderson_window : {0, 5}) {
    for (double relaxation : {1.0, 1.9}) {
      for (double weight_power : {0.0, 1.0}) {
        for (unsigned seed : {1u, 2u, 3u, 4u}) {
          SCOPED_TRACE(::testing::Message()
                       << "relaxation " << relaxation << " weight_power " << weight_power
                       << " anderson " << anderson_window << " seed " << seed);
          SmacofOptions options;
          options.anderson_window = anderson_window;
          options.relaxation = relaxation;
          options.weight_power = weight_power;
          options.tolerance = 0.0;
          options.max_iterations = 40;
          const Eigen::MatrixXd init = RandomConfiguration(60, 3, seed);
          const SmacofResult r = Smacof(D, init, options);
          ASSERT_EQ(r.stress_history.size(), static_cast<size_t>(r.iterations) + 1);
          for (size_t k = 1; k < r.stress_history.size(); ++k) {
            EXPECT_LE(r.stress_history[k], r.stress_history[k - 1]) << "iteration " << k;
          }
          // The recorded value is the stress of the iterate (checked independently, uniform
          // weights only since RawStress is unweighted); relative 1e-12 allows summation order.
          if (weight_power == 0.0) {
            for (int k : {0, 1, 5, r.iterations}) {
              options.max_iterations = k;
              const Eigen::MatrixXd Xk = Smacof(D, init, options).X;
              EXPECT_NEAR(RawStress(D, Xk), r.stress_history[k], 1e-12 * r.stress_history[0]);
            }
          }
        }
      }
    }
  }
}

TEST(Smacof, AccelerationNeedsFewerStressEvaluations) {
  const Eigen::MatrixXd P = BoxPoints(200, 4);
  const Eigen::MatrixXd D = CurvedDistances(P);
  SmacofOptions plain;
  plain.relaxation = 1.0;
  plain.anderson_window = 0;
  SmacofOptions relaxed = plain;
  relaxed.relaxation = 1.9;
  const SmacofOptions accelerated;  // defaults: relaxation and Anderson acceleration
  const Eigen::MatrixXd init = RandomConfiguration(200, 3, 21);
  const SmacofResult a = Smacof(D, init, plain);
  const SmacofResult b = Smacof(D, init, relaxed);
  const SmacofResult c = Smacof(D, init, accelerated);
  EXPECT_TRUE(a.converged && b.converged && c.converged);
  EXPECT_EQ(a.evaluations, a.iterations + 1);  // plain steps are never rejected
  EXPECT_LT(b.evaluations, a.evaluations);
  EXPECT_LT(c.evaluations, b.evaluations);
  // All reach the same local minimum from the same start (to the tolerance's precision).
  EXPECT_NEAR(b.normalized_stress, a.normalized_stress, 1e-3 * a.normalized_stress);
  EXPECT_NEAR(c.normalized_stress, a.normalized_stress, 1e-3 * a.normalized_stress);
}

TEST(Smacof, WeightedPathRecoversEuclideanPoints) {
  const Eigen::MatrixXd P = BoxPoints(80, 5);
  const Eigen::MatrixXd D = EuclideanDistances(P, P);
  SmacofOptions options;
  options.weight_power = 2.0;
  options.tolerance = 1e-12;
  options.max_iterations = 5000;
  const SmacofResult r = Smacof(D, P + 0.05 * RandomConfiguration(80, 3, 9), options);
  // As in the unweighted case: exact data, linear convergence, bound far above rounding.
  EXPECT_LT(RelativeResidual(P, r.X), 1e-5);
}

TEST(Smacof, TwoDimensionsAndInvalidInput) {
  const Eigen::MatrixXd P = BoxPoints(50, 6).leftCols(2);
  const Eigen::MatrixXd D = EuclideanDistances(P, P);
  const SmacofResult r = Smacof(D, ScaleToDistances(D, P));
  EXPECT_EQ(r.X.cols(), 2);
  EXPECT_LT(r.normalized_stress, 1e-9);  // exact 2D data from its own coordinates
  EXPECT_THROW(Smacof(D, Eigen::MatrixXd::Zero(49, 2)), InvalidInputError);
  EXPECT_THROW(Smacof(Eigen::MatrixXd::Zero(50, 49), P), InvalidInputError);
  Eigen::MatrixXd bad = D;
  bad(0, 1) = -1.0;
  EXPECT_THROW(Smacof(bad, P), InvalidInputError);
  SmacofOptions options;
  options.relaxation = 2.0;
  EXPECT_THROW(Smacof(D, P, options), ConfigError);
  std::string why;
  EXPECT_FALSE(options.IsValid(&why));
  EXPECT_NE(why.find("relaxation"), std::string::npos);
}

TEST(ClassicalMds, RecoversEuclideanPointsDenseAndLanczos) {
  for (int n : {100, 400}) {  // below and above dense_limit
    const Eigen::MatrixXd P = BoxPoints(n, 10 + n);
    const ClassicalMdsResult r = ClassicalMds(EuclideanDistances(P, P));
    // Exact Euclidean distances: classical MDS is exact up to rounding in the eigensolver.
    EXPECT_LT(RelativeResidual(P, r.X), 1e-8) << "n = " << n;
    EXPECT_GT(r.eigenvalues(0), r.eigenvalues(1));
    EXPECT_GT(r.eigenvalues(1), r.eigenvalues(2));
    // The eigenvalues are the principal second moments of the centred points.
    const Eigen::MatrixXd Pc = P.rowwise() - P.colwise().mean();
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> moments(Pc.transpose() * Pc);
    EXPECT_LT((r.eigenvalues - moments.eigenvalues().reverse()).norm(), 1e-8 * r.eigenvalues(0));
  }
}

TEST(ClassicalMds, LandmarkMdsReproducesLandmarksAndPlacesEuclideanQueries) {
  const Eigen::MatrixXd P = BoxPoints(300, 11);
  const Eigen::MatrixXd Q = BoxPoints(100, 12);
  const ClassicalMdsResult r = ClassicalMds(EuclideanDistances(P, P));
  const Eigen::MatrixXd at_landmarks = LandmarkMds(r, EuclideanDistances(P, P));
  EXPECT_LT((at_landmarks - r.X).norm(), 1e-9 * r.X.norm());  // exact up to rounding
  // Euclidean queries are placed exactly in the landmarks' frame: the joint set is rigid.
  Eigen::MatrixXd truth(400, 3), placed(400, 3);
  truth << P, Q;
  placed << r.X, LandmarkMds(r, EuclideanDistances(P, Q));
  EXPECT_LT(RelativeResidual(truth, placed), 1e-8);
  const std::vector<int> some = {5, 0, 99};
  const Eigen::MatrixXd subset = LandmarkMds(r, EuclideanDistances(P, Q), some);
  EXPECT_LT((subset.row(0) - placed.row(305)).norm(), 1e-12);
  EXPECT_THROW(LandmarkMds(r, EuclideanDistances(Q, Q)), InvalidInputError);
}

TEST(OutOfSample, PlacesEuclideanQueriesAndReproducesSamples) {
  const Eigen::MatrixXd P = BoxPoints(300, 13);
  const Eigen::MatrixXd Q = BoxPoints(200, 14);
  // Samples at their true positions, exact distances: the stress minimum (zero) is the true
  // point and Gauss-Newton converges to it quadratically; the bounds are rounding level.
  const Eigen::MatrixXd placed = PlaceOutOfSample(P, EuclideanDistances(P, Q));
  EXPECT_LT((placed - Q).cwiseAbs().maxCoeff(), 1e-10);
  const Eigen::MatrixXd self = PlaceOutOfSample(P, EuclideanDistances(P, P));
  EXPECT_LT((self - P).cwiseAbs().maxCoeff(), 1e-10);
  const Eigen::MatrixXd cols = PlaceOutOfSample(P, EuclideanDistances(P, Q), {7, 3});
  EXPECT_LT((cols.row(0) - placed.row(7)).norm(), 1e-12);
  EXPECT_THROW(PlaceOutOfSample(P, EuclideanDistances(Q, Q)), InvalidInputError);
  EXPECT_THROW(PlaceOutOfSample(P, EuclideanDistances(P, Q), {200}), InvalidInputError);
}

}  // namespace
}  // namespace symembed

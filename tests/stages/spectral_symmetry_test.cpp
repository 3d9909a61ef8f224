#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "core/errors.h"
#include "core/knn.h"
#include "core/primitives.h"
#include "core/procrustes.h"
#include "registry/registry.h"
#include "stages/symmetry/plane2d.h"
#include "stages/symmetry/reflection_search.h"
#include "stages/symmetry/spectral_symmetry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// A box with three different side lengths: its symmetries are the mirrors about x = 0, y = 0,
// z = 0 and their compositions; the mesh is mirror-symmetric vertex for vertex.
Surface TestBox() { return BoxMesh(8, 1.0, 1.7, 2.6); }

std::vector<int> AllVertices(int n) {
  std::vector<int> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  return ids;
}

// sigma(i) = the vertex nearest to vertex i mirrored about coordinate plane `axis` = 0.
std::vector<int> MirrorMap(const Surface& s, int axis, double* max_residual) {
  Eigen::MatrixXd Q = s.V;
  Q.col(axis) = -Q.col(axis);
  Eigen::VectorXd residual;
  const std::vector<int> sigma = KnnIndex(s.V).Nearest(Q, &residual, 1);
  *max_residual = residual.maxCoeff();
  return sigma;
}

TEST(SpectralSymmetry, MirrorsCommuteWithTheEigenfunctionsAndAPermutationDoesNot) {
  const Surface box = TestBox();
  const Eigen::MatrixXd G = SampleSpectralCoordinates(box, AllVertices(box.NumVertices()), 8);
  ASSERT_EQ(G.rows(), box.NumVertices());
  ASSERT_EQ(G.cols(), 8);
  for (int axis = 0; axis < 3; ++axis) {
    double residual = 0.0;
    const std::vector<int> mirror = MirrorMap(box, axis, &residual);
    ASSERT_LT(residual, 1e-9);  // the mesh is exactly symmetric
    // Exact symmetry, simple eigenvalues: only the eigensolver's tolerance is left.
    EXPECT_GT(SpectralConsistency(G, mirror), 0.999) << "axis " << axis;
  }
  std::vector<int> shuffled = AllVertices(box.NumVertices());
  std::mt19937 rng(7);
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  // A random self map correlates nothing: about 1/sqrt(#V) per eigenfunction.
  EXPECT_LT(SpectralConsistency(G, shuffled), 0.2);
}

// A box with a square cross-section (x and y sides equal) has pairs of (nearly, up to its
// triangulation) repeated eigenvalues; any basis of such an eigenspace is as valid as the
// eigensolver's. In a basis turned by 30 degrees within each pair, the mirror across the diagonal
// plane x = y maps an eigenfunction onto a mixture of the pair: eigenfunction by eigenfunction
// it looks like no symmetry, eigenspace by eigenspace it is exact. A random self map stays low
// either way.
TEST(SpectralSymmetry, ConsistencyCountsRepeatedEigenvaluesAsOneEigenspace) {
  const Surface box = BoxMesh(8, 1.3, 1.3, 2.6);
  Eigen::VectorXd evals;
  Eigen::MatrixXd G = SampleSpectralCoordinates(box, AllVertices(box.NumVertices()), 8, &evals);
  ASSERT_EQ(evals.size(), 8);
  int pairs = 0;
  for (int j = 0; j + 1 < 8; ++j) {
    if (evals(j + 1) - evals(j) >= 0.01 * evals(j)) continue;
    const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
    const Eigen::VectorXd a = G.col(j), b = G.col(j + 1);
    G.col(j) = c * a + s * b;
    G.col(j + 1) = -s * a + c * b;
    ++pairs;
    ++j;
  }
  ASSERT_GE(pairs, 2) << evals.transpose();
  Eigen::MatrixXd swapped = box.V;
  swapped.col(0) = box.V.col(1);
  swapped.col(1) = box.V.col(0);
  Eigen::VectorXd residual;
  const std::vector<int> diagonal = KnnIndex(box.V).Nearest(swapped, &residual, 1);
  ASSERT_LT(residual.maxCoeff(), 1e-9);

  EXPECT_LT(SpectralConsistency(G, diagonal), 0.9);
  EXPECT_GT(SpectralConsistency(G, diagonal, evals, 0.05), 0.99);
  // Tolerance 0 is the eigenfunction-by-eigenfunction measure.
  EXPECT_NEAR(SpectralConsistency(G, diagonal, evals, 0.0), SpectralConsistency(G, diagonal),
              1e-12);
  std::vector<int> shuffled = AllVertices(box.NumVertices());
  std::mt19937 rng(7);
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  EXPECT_LT(SpectralConsistency(G, shuffled, evals, 0.05), 0.3);
  EXPECT_THROW(SpectralConsistency(G, diagonal, Eigen::VectorXd::Ones(3), 0.05),
               InvalidInputError);
}

TEST(SpectralSymmetry, SignFlipsFindTheMirrorsOfABox) {
  const Surface box = TestBox();
  const Eigen::MatrixXd G = SampleSpectralCoordinates(box, AllVertices(box.NumVertices()), 6);
  const std::vector<SignFlipCandidate> flips = SignFlipCandidates(G, 7, 0.1);
  ASSERT_EQ(flips.size(), 7u);
  for (size_t k = 1; k < flips.size(); ++k) EXPECT_LE(flips[k - 1].score, flips[k].score);
  for (int axis = 0; axis < 3; ++axis) {
    double residual = 0.0;
    const std::vector<int> mirror = MirrorMap(box, axis, &residual);
    int best_agreement = 0;
    for (const SignFlipCandidate& f : flips) {
      int agree = 0;
      for (size_t i = 0; i < mirror.size(); ++i) agree += f.sigma[i] == mirror[i];
      best_agreement = std::max(best_agreement, agree);
    }
    // Each mirror is one sign pattern of the (simple) eigenfunctions; its nearest neighbours
    // are exact up to the eigensolver's tolerance, except at a few points of the mesh where
    // two vertices lie equally near.
    EXPECT_GT(best_agreement, 0.98 * box.NumVertices()) << "axis " << axis;
  }
}

// Every sign pattern searched on the kd-tree, pattern by pattern, and the lowest scores kept:
// what SignFlipCandidates returns from its sweep over the patterns.
std::vector<SignFlipCandidate> EverySignFlip(const Eigen::MatrixXd& G, int keep,
                                             double outlier_distance) {
  const KnnIndex index(G);
  std::vector<SignFlipCandidate> all;
  for (unsigned pattern = 1; pattern < (1u << G.cols()); ++pattern) {
    Eigen::MatrixXd Q = G;
    for (int j = 0; j < G.cols(); ++j) {
      if (pattern >> j & 1u) Q.col(j) = -Q.col(j);
    }
    SignFlipCandidate c;
    c.pattern = pattern;
    c.sigma = index.Nearest(Q, &c.residual, 1);
    c.score = TruncatedScore(c.residual, RmsRadius(G), outlier_distance);
    all.push_back(std::move(c));
  }
  // Equal scores (the box's mirrors give some) in partial_sort's order, as SignFlipCandidates
  // orders them.
  const size_t kept = std::min<size_t>(keep, all.size());
  std::partial_sort(all.begin(), all.begin() + kept, all.end(),
                    [](const SignFlipCandidate& a, const SignFlipCandidate& b) {
                      return a.score < b.score;
                    });
  all.resize(kept);
  return all;
}

TEST(SpectralSymmetry, SignFlipCandidatesAreThoseOfTheKdTreePatternByPattern) {
  // The figure's samples in 8 coordinates (the default) and the box's in 6; few kept and many;
  // a cap that truncates most residuals and one that truncates few.
  const Surface figure = testing::SymmetricFigure(1, true);
  const Surface box = TestBox();
  const Eigen::MatrixXd Gs[] = {
      SampleSpectralCoordinates(figure, AllVertices(figure.NumVertices()), 8),
      SampleSpectralCoordinates(box, AllVertices(box.NumVertices()), 6)};
  for (const Eigen::MatrixXd& G : Gs) {
    for (const int keep : {1, 4, 40}) {
      for (const double outlier : {0.1, 2.0}) {
        const std::vector<SignFlipCandidate> fast = SignFlipCandidates(G, keep, outlier);
        const std::vector<SignFlipCandidate> every = EverySignFlip(G, keep, outlier);
        ASSERT_EQ(fast.size(), every.size());
        for (size_t i = 0; i < fast.size(); ++i) {
          EXPECT_EQ(fast[i].pattern, every[i].pattern) << keep << " " << outlier << " " << i;
          EXPECT_EQ(fast[i].score, every[i].score);
          EXPECT_EQ(fast[i].sigma, every[i].sigma);
          EXPECT_EQ(fast[i].residual, every[i].residual);
        }
      }
    }
  }
}

TEST(SpectralSymmetry, RejectsBadOptions) {
  Registry registry;
  RegisterBuiltinStages(registry);
  for (const char* yaml : {"{type: plane2d, spectral_eigenfunctions: 13}",
                           "{type: plane2d, spectral_min_consistency: 1.5}",
                           "{type: plane2d, spectral_weight: -1}",
                           "{type: plane2d, spectral_candidates: -1}",
                           "{type: plane2d, spectral_eigenvalue_tolerance: -0.1}",
                           "{type: plane2d, spectral_eigenvalue_tolerance: 2}"}) {
    EXPECT_THROW(registry.Create("symmetry", YAML::Load(yaml), "t.yaml", "pipeline.symmetry"),
                 ConfigError)
        << yaml;
  }
}

TEST(Plane2d, SpectralCheckKeepsTheFigurePlane) {
  std::vector<int> mirror;
  const Surface figure = testing::SymmetricFigure(1, true, &mirror);
  const std::vector<int> samples = AllVertices(figure.NumVertices());
  Eigen::MatrixXd D(samples.size(), figure.NumVertices());
  for (size_t s = 0; s < samples.size(); ++s) {
    D.row(s) = (figure.V.rowwise() - figure.V.row(samples[s])).rowwise().norm().transpose();
  }
  const Plane2dOptions options;
  const Eigen::MatrixXd G =
      SampleSpectralCoordinates(figure, samples, options.spectral.num_eigenfunctions);
  const SymmetryResult r = DetectSymmetryPlane2d(D, samples, figure.V, options, G);
  // The figure is exactly symmetric about x = 0: the self map chosen by distances commutes with
  // the eigenfunctions well enough, and the plane is the one found without the check.
  EXPECT_GT(std::abs(r.normal.x()), 0.9999) << r.status.message;
  int correct = 0;
  for (size_t i = 0; i < samples.size(); ++i) correct += r.sigma[i] == mirror[i];
  EXPECT_GT(correct, 0.99 * samples.size()) << r.status.message;
}

}  // namespace
}  // namespace symembed

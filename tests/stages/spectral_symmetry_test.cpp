#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "core/errors.h"
#include "core/knn.h"
#include "core/primitives.h"
#include "registry/registry.h"
#include "stages/symmetry/plane2d.h"
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

TEST(SpectralSymmetry, RejectsBadOptions) {
  Registry registry;
  RegisterBuiltinStages(registry);
  for (const char* yaml : {"{type: plane2d, spectral_eigenfunctions: 13}",
                           "{type: plane2d, spectral_min_consistency: 1.5}",
                           "{type: plane2d, spectral_weight: -1}",
                           "{type: plane2d, spectral_candidates: -1}"}) {
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

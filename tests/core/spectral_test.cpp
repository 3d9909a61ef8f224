#include "core/spectral.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "core/laplacian.h"
#include "core/primitives.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// Checks every residual ||L phi - lambda M phi|| relative to (lambda + lambda_max) ||M phi||
// (lambda_max: the largest computed eigenvalue, the scale of the problem; the near-zero first
// eigenvalue makes a purely relative residual meaningless), and the largest entry of
// |Phi^T M Phi - I|.
void CheckEigenpairs(const Surface& s, const LaplaceBasis& b, MassType mass, double residual_tol,
                     double orthonormality_tol) {
  const Eigen::SparseMatrix<double> L = CotanStiffness(s);
  const Eigen::SparseMatrix<double> M = MassMatrix(s, mass);
  for (int j = 0; j < b.NumEigenpairs(); ++j) {
    const Eigen::VectorXd Lphi = L * b.evecs.col(j);
    const Eigen::VectorXd Mphi = M * b.evecs.col(j);
    const double scale = (std::abs(b.evals(j)) + b.evals.maxCoeff()) * Mphi.norm();
    EXPECT_LT((Lphi - b.evals(j) * Mphi).norm() / scale, residual_tol) << "eigenpair " << j;
    if (j > 0) {
      EXPECT_GE(b.evals(j), b.evals(j - 1)) << "eigenvalues not ascending at " << j;
    }
  }
  const Eigen::MatrixXd gram = b.evecs.transpose() * (M * b.evecs);
  const int k = b.NumEigenpairs();
  EXPECT_LT((gram - Eigen::MatrixXd::Identity(k, k)).cwiseAbs().maxCoeff(), orthonormality_tol);
}

TEST(LaplaceBasis, SatisfiesGeneralisedProblemLumpedAndConsistent) {
  const Surface s = testing::BumpyBlob(12);
  for (MassType mass : {MassType::kLumped, MassType::kConsistent}) {
    LaplaceBasisOptions options;
    options.k = 60;
    options.mass = mass;
    const LaplaceBasis b = ComputeLaplaceBasis(s, options);
    ASSERT_EQ(b.NumEigenpairs(), 60);
    ASSERT_EQ(b.NumVertices(), s.NumVertices());
    // Converged to tolerance 1e-10 on the eigenvalues; residuals of 1e-6 relative leave margin for
    // the conditioning of the shifted factorisation.
    CheckEigenpairs(s, b, mass, 1e-6, 1e-8);
    // Closed connected surface: one zero eigenvalue, then strictly positive.
    EXPECT_NEAR(b.evals(0), 0.0, 1e-8);
    EXPECT_GT(b.evals(1), 1e-3);
    EXPECT_TRUE(b.mass.isApprox(VertexAreas(s)));
  }
}

TEST(LaplaceBasis, SphereMatchesSphericalHarmonicBands) {
  // Eigenvalues of the radius-R sphere: l (l + 1) / R^2 with multiplicity 2 l + 1.
  const double R = 2.0;
  const Surface s = Icosphere(4, R);  // 2562 vertices
  // k cuts no band (36 = bands l = 0..5 complete) and k = 40 cuts band l = 6: both must give the
  // full multiplicities of the complete bands.
  for (int k : {36, 40}) {
    LaplaceBasisOptions options;
    options.k = k;
    const LaplaceBasis b = ComputeLaplaceBasis(s, options);
    int j = 0;
    for (int l = 0; j < k; ++l) {
      const double expected = l * (l + 1) / (R * R);
      for (int m = 0; m < 2 * l + 1 && j < k; ++m, ++j) {
        // The cotan Laplacian converges as O(h^2): at level 4 (edge ~ 0.07 R) bands l <= 6 are
        // within 2% (measured worst 1.6% at l = 6, lumped mass).
        EXPECT_NEAR(b.evals(j), expected, 0.02 * expected + 1e-8) << "k=" << k << " l=" << l;
      }
    }
    CheckEigenpairs(s, b, MassType::kLumped, 1e-6, 1e-8);
  }
}

TEST(LaplaceBasis, SquareWithBoundaryHasNeumannSpectrum) {
  // Unit square, Neumann condition: pi^2 (a^2 + b^2) for a, b >= 0.
  const Surface s = GridMesh(41, 41);
  LaplaceBasisOptions options;
  options.k = 6;
  const LaplaceBasis b = ComputeLaplaceBasis(s, options);
  const double pi2 = M_PI * M_PI;
  const double expected[] = {0.0, pi2, pi2, 2 * pi2, 4 * pi2, 4 * pi2};
  for (int j = 0; j < 6; ++j) {
    // h = 1/40: the discretisation error is below 1% of the eigenvalue for these modes.
    EXPECT_NEAR(b.evals(j), expected[j], 0.01 * expected[j] + 1e-8) << j;
  }
  CheckEigenpairs(s, b, MassType::kLumped, 1e-6, 1e-8);
}

TEST(LaplaceBasis, UnreferencedVertexGetsZeroRowAndLeavesSpectrumUnchanged) {
  const Surface s = testing::BumpyBlob(8);
  Surface with_extra = s;
  with_extra.V.conservativeResize(s.NumVertices() + 1, 3);
  with_extra.V.row(s.NumVertices()) << 5.0, 5.0, 5.0;
  LaplaceBasisOptions options;
  options.k = 20;
  const LaplaceBasis a = ComputeLaplaceBasis(s, options);
  const LaplaceBasis b = ComputeLaplaceBasis(with_extra, options);
  ASSERT_EQ(b.NumVertices(), s.NumVertices() + 1);
  // Same problem on the referenced vertices: eigenvalues agree to the solver tolerance.
  EXPECT_LT((a.evals - b.evals).cwiseAbs().maxCoeff(), 1e-7 * a.evals.maxCoeff());
  EXPECT_EQ(b.evecs.row(s.NumVertices()).cwiseAbs().maxCoeff(), 0.0);
  EXPECT_EQ(b.mass(s.NumVertices()), 0.0);
}

TEST(LaplaceBasis, TwoComponentsGiveTwoZeroEigenvalues) {
  const Surface a = Icosphere(2), b = Icosphere(2);
  Surface s;
  s.V.resize(a.NumVertices() * 2, 3);
  s.V << a.V, b.V.rowwise() + Eigen::RowVector3d(3, 0, 0);
  s.F.resize(a.NumFaces() * 2, 3);
  s.F << a.F, b.F.array() + a.NumVertices();
  LaplaceBasisOptions options;
  options.k = 4;
  const LaplaceBasis basis = ComputeLaplaceBasis(s, options);
  EXPECT_NEAR(basis.evals(0), 0.0, 1e-8);
  EXPECT_NEAR(basis.evals(1), 0.0, 1e-8);
  EXPECT_GT(basis.evals(2), 1.0);  // first nonzero of the unit sphere is ~2
}

TEST(LaplaceBasis, RejectsBadOptionsAndTooLargeK) {
  LaplaceBasisOptions options;
  std::string error;
  options.k = 0;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("k must be >= 1"), std::string::npos) << error;
  EXPECT_THROW(ComputeLaplaceBasis(Icosphere(1), options), ConfigError);
  options.k = 42;  // Icosphere(1) has 42 vertices
  EXPECT_THROW(ComputeLaplaceBasis(Icosphere(1), options), InvalidInputError);
}

TEST(LaplaceBasis, LeadingEigenpairsAreThePrefixOrAnError) {
  const Surface s = testing::BumpyBlob(6);
  LaplaceBasisOptions options;
  options.k = 10;
  const LaplaceBasis basis = ComputeLaplaceBasis(s, options);
  EXPECT_EQ(LeadingEigenpairs(basis, -1).evecs, basis.evecs);
  const LaplaceBasis five = LeadingEigenpairs(basis, 5);
  EXPECT_EQ(five.NumEigenpairs(), 5);
  EXPECT_EQ(five.evecs, basis.evecs.leftCols(5));
  EXPECT_EQ(five.evals, basis.evals.head(5));
  EXPECT_EQ(five.mass, basis.mass);
  EXPECT_THROW(LeadingEigenpairs(basis, 11), InvalidInputError);
  EXPECT_THROW(LeadingEigenpairs(LaplaceBasis{}, 1), InvalidInputError);
  LaplaceBasis broken = basis;
  broken.mass.resize(3);
  EXPECT_THROW(LeadingEigenpairs(broken, 5), InvalidInputError);
  // Into a basis that held more eigenpairs (a thread's reused storage): the same five.
  LaplaceBasis reused = basis;
  LeadingEigenpairs(basis, 5, &reused);
  EXPECT_EQ(reused.evecs, five.evecs);
  EXPECT_EQ(reused.evals, five.evals);
  EXPECT_EQ(reused.mass, five.mass);
}

}  // namespace
}  // namespace symembed

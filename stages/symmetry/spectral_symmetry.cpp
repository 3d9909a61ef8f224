#include "stages/symmetry/spectral_symmetry.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/errors.h"
#include "core/knn.h"
#include "core/procrustes.h"
#include "core/sign_flip_nearest.h"
#include "core/spectral.h"
#include "stages/symmetry/reflection_search.h"

namespace symembed {

namespace {

// Number of leading eigenvalues that are ~0 (one per connected component), relative to the
// scale 1 / area of the eigenvalues of a surface of that area.
int CountZeroEigenvalues(const Eigen::VectorXd& evals, double area) {
  const double tolerance = 1e-8 / std::max(area, 1e-300);
  int zeros = 0;
  while (zeros < evals.size() && std::abs(evals(zeros)) <= tolerance) ++zeros;
  return zeros;
}

}  // namespace

Eigen::MatrixXd SampleSpectralCoordinates(const Surface& surface, const std::vector<int>& samples,
                                          int num_eigenfunctions, Eigen::VectorXd* evals) {
  SYMEMBED_CHECK(num_eigenfunctions >= 1, "num_eigenfunctions must be >= 1");
  const double area = TotalArea(surface);
  LaplaceBasisOptions options;
  options.k = num_eigenfunctions + 1;
  LaplaceBasis basis;
  int zeros = 0;
  for (;;) {
    basis = ComputeLaplaceBasis(surface, options);
    zeros = CountZeroEigenvalues(basis.evals, area);
    if (basis.NumEigenpairs() >= zeros + num_eigenfunctions) break;
    // Several components, one ~0 eigenvalue each: ask for more (ComputeLaplaceBasis throws when
    // the surface has too few vertices).
    options.k = zeros < basis.NumEigenpairs() ? zeros + num_eigenfunctions : 2 * options.k;
  }
  if (zeros == 0) {
    throw InvalidInputError("spectral symmetry: the Laplace-Beltrami basis has no ~0 eigenvalue");
  }
  Eigen::MatrixXd G(samples.size(), num_eigenfunctions);
  for (size_t i = 0; i < samples.size(); ++i) {
    if (samples[i] < 0 || samples[i] >= basis.NumVertices()) {
      throw InvalidInputError("spectral symmetry: sample id out of range");
    }
    for (int j = 0; j < num_eigenfunctions; ++j) {
      G(i, j) = basis.evecs(samples[i], zeros + j) / std::sqrt(basis.evals(zeros + j));
    }
  }
  if (evals) *evals = basis.evals.segment(zeros, num_eigenfunctions);
  return G;
}

std::vector<SignFlipCandidate> SignFlipCandidates(const Eigen::MatrixXd& G, int num_candidates,
                                                  double outlier_distance, int threads) {
  const int k = static_cast<int>(G.cols());
  SYMEMBED_CHECK(k >= 1 && k <= 12, "between 1 and 12 spectral coordinates");
  std::vector<SignFlipCandidate> all;
  if (num_candidates <= 0 || G.rows() < 2) return all;
  const KnnIndex index(G);
  const SignFlipNeighbours neighbours = NearestUnderSignFlips(G, index, threads);
  const double size = RmsRadius(G);
  const int n = static_cast<int>(G.rows());
  auto residual = [&](unsigned pattern) {
    return Eigen::Map<const Eigen::VectorXd>(
        neighbours.distances.data() + static_cast<size_t>(pattern - 1) * n, n);
  };
  std::vector<unsigned> patterns;
  std::vector<double> scores(1u << k);
  for (unsigned pattern = 1; pattern < (1u << k); ++pattern) {
    patterns.push_back(pattern);
    scores[pattern] = TruncatedScore(residual(pattern), size, outlier_distance);
  }
  const size_t keep = std::min<size_t>(num_candidates, patterns.size());
  std::partial_sort(patterns.begin(), patterns.begin() + keep, patterns.end(),
                    [&](unsigned a, unsigned b) { return scores[a] < scores[b]; });
  for (size_t t = 0; t < keep; ++t) {
    const int* nearest = neighbours.nearest.data() + static_cast<size_t>(patterns[t] - 1) * n;
    SignFlipCandidate c;
    c.pattern = patterns[t];
    c.sigma.assign(nearest, nearest + n);
    c.residual = residual(patterns[t]);
    c.score = scores[patterns[t]];
    c.fixed_fraction = FixedFraction(c.sigma);
    all.push_back(std::move(c));
  }
  return all;
}

double SpectralConsistency(const Eigen::MatrixXd& G, const std::vector<int>& sigma,
                           const Eigen::VectorXd& evals, double tolerance) {
  SYMEMBED_CHECK(static_cast<int>(sigma.size()) == G.rows(), "sigma does not match G");
  if (evals.size() != 0 && evals.size() != G.cols()) {
    throw InvalidInputError("spectral consistency: " + std::to_string(evals.size()) +
                            " eigenvalues for " + std::to_string(G.cols()) + " eigenfunctions");
  }
  const int k = static_cast<int>(G.cols());
  if (k == 0) return 1.0;
  // Unit columns of G and of G o sigma; a zero column contributes 0.
  Eigen::MatrixXd U = G, V(G.rows(), k);
  for (int i = 0; i < G.rows(); ++i) V.row(i) = G.row(sigma[i]);
  std::vector<bool> zero(k, false);
  for (int j = 0; j < k; ++j) {
    const double nu = U.col(j).norm(), nv = V.col(j).norm();
    zero[j] = !(nu > 0.0 && nv > 0.0);
    if (!zero[j]) {
      U.col(j) /= nu;
      V.col(j) /= nv;
    }
  }
  double sum = 0.0;
  for (int j = 0; j < k; ++j) {
    if (zero[j]) continue;
    std::vector<int> space;
    for (int m = 0; m < k; ++m) {
      const bool near = m == j || (evals.size() == k && tolerance > 0.0 &&
                                   std::abs(evals(m) - evals(j)) <= tolerance * std::abs(evals(j)));
      if (near && !zero[m]) space.push_back(m);
    }
    if (space.size() == 1) {
      sum += std::abs(U.col(j).dot(V.col(j)));
      continue;
    }
    // Squared norm of the projection of v_j onto span(B): b^T (B^T B)^-1 b with b = B^T v_j.
    Eigen::MatrixXd B(G.rows(), space.size());
    for (size_t q = 0; q < space.size(); ++q) B.col(q) = U.col(space[q]);
    const Eigen::VectorXd b = B.transpose() * V.col(j);
    const Eigen::VectorXd x = (B.transpose() * B).ldlt().solve(b);
    sum += std::sqrt(std::clamp(b.dot(x), 0.0, 1.0));
  }
  return sum / k;
}

}  // namespace symembed

#include "core/fmap/descriptors.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>

#include "core/errors.h"

namespace symembed {

Eigen::MatrixXd EnergyWeights(const Eigen::VectorXd& evals, const Eigen::VectorXd& energies,
                              double sigma) {
  double lambda_1, lambda_max;
  PositiveEigenvalueRange(evals, &lambda_1, &lambda_max);
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(evals.size(), energies.size());
  for (int j = 0; j < evals.size(); ++j) {
    if (!(lambda_1 > 0.0 && evals(j) >= lambda_1)) continue;
    const double e_j = std::log(evals(j));
    for (int e = 0; e < energies.size(); ++e) {
      const double d = energies(e) - e_j;
      G(j, e) = std::exp(-d * d / (2.0 * sigma * sigma));
    }
  }
  for (int e = 0; e < energies.size(); ++e) {
    const double total = G.col(e).sum();
    if (total > 0.0) G.col(e) /= total;
  }
  return G;
}

WksProducts ComputeWksProducts(const LaplaceBasis& b, int k, int n) {
  SYMEMBED_CHECK(n <= b.NumEigenpairs() && k <= b.NumEigenpairs(),
                 "the basis has fewer eigenpairs than the weights or k");
  const Eigen::MatrixXd phi2 = b.evecs.leftCols(n).array().square().matrix();
  WksProducts out;
  out.P = b.evecs.leftCols(k).transpose() * (b.mass.asDiagonal() * phi2);
  const Eigen::MatrixXd W = b.mass.cwiseMax(0.0).cwiseSqrt().asDiagonal() * phi2;
  out.Q = Eigen::MatrixXd::Zero(n, n);
  out.Q.selfadjointView<Eigen::Lower>().rankUpdate(W.transpose());
  out.Q = out.Q.selfadjointView<Eigen::Lower>();
  return out;
}

// (Phi_k^T M Phi2) G with the norms from G^T (Phi2^T M Phi2) G: the products over the #V rows do
// not depend on the energies.
Eigen::MatrixXd WksCoefficients(const WksProducts& products, const Eigen::MatrixXd& G) {
  SYMEMBED_CHECK(products.P.cols() == G.rows() && products.Q.rows() == G.rows(),
                 "the signature products are for " << products.Q.rows() << " eigenpairs, the "
                                                   << "weights for " << G.rows());
  Eigen::MatrixXd A = products.P * G;
  for (int e = 0; e < G.cols(); ++e) {
    const double norm = std::sqrt(std::max(G.col(e).dot(products.Q * G.col(e)), 0.0));
    if (norm > 0.0) A.col(e) /= norm;
  }
  return A;
}

Eigen::MatrixXd WaveKernelSignature(const LaplaceBasis& basis, const Eigen::VectorXd& energies,
                                    double sigma) {
  return basis.evecs.array().square().matrix() * EnergyWeights(basis.evals, energies, sigma);
}

Eigen::VectorXd WksEnergies(const Eigen::VectorXd& evals_a, const Eigen::VectorXd& evals_b,
                            int count, double sigma_units, double* sigma) {
  double a1, amax, b1, bmax;
  PositiveEigenvalueRange(evals_a, &a1, &amax);
  PositiveEigenvalueRange(evals_b, &b1, &bmax);
  if (!(a1 > 0.0) || !(b1 > 0.0)) throw InvalidInputError("flip descriptor: no positive eigenvalue");
  const double e_1 = 0.5 * (std::log(a1) + std::log(b1));
  const double e_max = 0.5 * (std::log(amax) + std::log(bmax));
  // Spacing delta of `count` energies in [e_1 + 2 sigma, e_max - 2 sigma] with sigma =
  // sigma_units * delta: (count - 1) delta + 4 sigma_units delta = e_max - e_1.
  const double delta = (e_max - e_1) / std::max(count - 1 + 4.0 * sigma_units, 1.0);
  *sigma = sigma_units * delta;
  Eigen::VectorXd energies(count);
  for (int e = 0; e < count; ++e) energies(e) = e_1 + 2.0 * *sigma + e * delta;
  return energies;
}

Eigen::MatrixXd DescriptorFunctionalMap(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                        const Eigen::VectorXd& evals_s,
                                        const Eigen::VectorXd& evals_t, double mu) {
  const int k = static_cast<int>(A.rows());
  if (B.rows() != k || A.cols() != B.cols() || evals_s.size() < k || evals_t.size() < k) {
    throw InvalidInputError("flip descriptor: descriptor coefficients and eigenvalues disagree");
  }
  const double scale = 0.5 * (evals_s(k - 1) + evals_t(k - 1));
  if (!(scale > 0.0)) throw InvalidInputError("flip descriptor: k-th eigenvalue is not positive");
  const Eigen::VectorXd ls = evals_s.head(k) / scale, lt = evals_t.head(k) / scale;
  const double weight = mu * B.squaredNorm() / k;
  const Eigen::MatrixXd BBt = B * B.transpose();
  const Eigen::MatrixXd ABt = A * B.transpose();
  Eigen::MatrixXd C(k, k);
  for (int i = 0; i < k; ++i) {
    // Row i: c_i (B B^T + weight diag_j (ls_i - lt_j)^2) = A_i B^T.
    Eigen::MatrixXd H = BBt;
    for (int j = 0; j < k; ++j) H(j, j) += weight * (ls(i) - lt(j)) * (ls(i) - lt(j));
    // A small ridge keeps rows without commutativity weight (i = j, equal eigenvalues) solvable.
    H.diagonal().array() += 1e-10 * std::max(BBt.trace() / k, 1e-300);
    C.row(i) = Eigen::LDLT<Eigen::MatrixXd>(H).solve(ABt.row(i).transpose()).transpose();
  }
  return C;
}

}  // namespace symembed

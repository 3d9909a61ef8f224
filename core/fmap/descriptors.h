// Wave kernel signatures [Aubry, Schlickewei & Cremers 2011] in a Laplace-Beltrami basis, and the
// functional map that preserves descriptors and commutes with the Laplacians [Ovsjanikov et al.
// 2012, Functional maps]. Shapes: #V rows per basis, k x q coefficient matrices; energies are
// log-eigenvalues. Throws InvalidInputError for inconsistent inputs (as each function says).
#pragma once

#include <Eigen/Core>

#include "core/spectral.h"

namespace symembed {

// Wave kernel signatures WKS(x, e) = sum_j phi_j(x)^2 g_j(e) / sum_j g_j(e), g_j(e) =
// exp(-(e - log lambda_j)^2 / (2 sigma^2)), over the eigenpairs with positive eigenvalues
// (PositiveEigenvalueRange, core/spectral.h).
// energies: the log-energies e. Returns #V x energies.size().
Eigen::MatrixXd WaveKernelSignature(const LaplaceBasis& basis, const Eigen::VectorXd& energies,
                                    double sigma);

// The Gaussian weights g_j(e) / sum_j g_j(e) of WaveKernelSignature (eigenpairs x energies), so
// that the signatures are Phi2 G for the squared eigenfunctions Phi2.
Eigen::MatrixXd EnergyWeights(const Eigen::VectorXd& evals, const Eigen::VectorXd& energies,
                              double sigma);

// What WksCoefficients needs of one shape's basis, whatever the energies: the products over its
// #V rows, P = Phi_k^T M Phi2 (k x n) and Q = Phi2^T M Phi2 (n x n), Phi2 the squares of the
// first n eigenfunctions. Per shape; the energies depend on both shapes of a pair.
struct WksProducts {
  Eigen::MatrixXd P;
  Eigen::MatrixXd Q;
};
WksProducts ComputeWksProducts(const LaplaceBasis& basis, int k, int n);

// The coefficients Phi_k^T M D (k x energies) of the signatures D = Phi2 G (Phi2 the squares of
// the first G.rows() eigenfunctions) in the first k eigenfunctions, each signature first scaled
// to unit M-norm so that every energy weighs the same.
Eigen::MatrixXd WksCoefficients(const WksProducts& products, const Eigen::MatrixXd& G);

// The log-energies shared by a pair: `count` evenly spaced in [e_1 + 2 sigma, e_max - 2 sigma],
// e_1 and e_max the means over the two spectra of the logs of the ends of
// PositiveEigenvalueRange (core/spectral.h), sigma = sigma_units * spacing. Writes the absolute
// sigma to *sigma. Throws InvalidInputError when a spectrum has no positive eigenvalue.
Eigen::VectorXd WksEnergies(const Eigen::VectorXd& evals_a, const Eigen::VectorXd& evals_b,
                            int count, double sigma_units, double* sigma);

// The k x k functional map (target coefficients to source coefficients, the convention of
// core/fmap/functional_map.h) minimising ||C B - A||^2 + mu' ||Lambda_s C - C Lambda_t||^2
// for descriptor coefficients A (source) and B (target), k x q, with eigenvalues divided by the
// mean k-th eigenvalue and mu' = mu ||B||_F^2 / k. Solved row by row (the commutativity term is
// diagonal per row).
Eigen::MatrixXd DescriptorFunctionalMap(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                        const Eigen::VectorXd& evals_s,
                                        const Eigen::VectorXd& evals_t, double mu);

}  // namespace symembed

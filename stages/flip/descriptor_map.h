// Descriptor term of the flip scorers: which candidate rotation agrees with a functional map
// computed from wave kernel signatures alone, independently of the canonical embeddings.
//
// The orientation term (orientation.h) separates candidates through ZoomOut from each
// candidate's map, which starts at a few eigenfunctions. On a thin human whose first
// eigenfunctions do not tell front from back, ZoomOut from the rotation by pi about the vertical
// axis can settle on a front-back reflection, so the term cannot reject it. The descriptor map
// starts from no map at all: the functional map C (k x k) minimising
//     || C B - A ||^2 + mu || Lambda_s C - C Lambda_t ||^2
// with A, B the coefficients of the wave kernel signatures [Aubry et al. 2011] of source and
// target in their first k eigenfunctions (descriptor preservation and commutativity with the
// Laplace-Beltrami operators, [Ovsjanikov et al. 2012] Functional maps), and its point map on
// the source samples. Both wave kernel signatures and the commutativity are invariant under the
// left-right symmetry, so C cannot tell left from right, and the term compares each candidate with
// the map along the in-plane axes of the canonical frame only (axis 0 is the symmetry plane's
// normal), where the candidates differ by turns about axis 1 or axis 2. The wave kernel
// signatures tell a quadruped's front from its back but often not a human's, so the default
// compares along axis 1 only (axes = 1; docs/analysis.md, "Measurements behind the defaults").
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "core/spectral.h"

namespace symembed {

struct DescriptorMapOptions {
  int k = 30;          // basis size of the functional map (both bases need `eigenpairs`)
  int eigenpairs = 60; // eigenpairs the wave kernel signatures are built from (>= k)
  int energies = 100;  // number of wave kernel signature energies
  double sigma = 7.0;  // energy bandwidth in units of the energy spacing [Aubry et al. 2011]
  double mu = 1e-2;    // weight of the commutativity term, relative (see DescriptorFunctionalMap)
  int samples = 300;   // source samples the point map is computed on
  // In-plane axes compared: 1 (the first in-plane axis of the canonical frame only) or 2 (both).
  int axes = 1;

  bool IsValid(std::string* error) const;
};

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
// stages/refine/functional_map.h) minimising ||C B - A||^2 + mu' ||Lambda_s C - C Lambda_t||^2
// for descriptor coefficients A (source) and B (target), k x q, with eigenvalues divided by the
// mean k-th eigenvalue and mu' = mu ||B||_F^2 / k. Solved row by row (the commutativity term is
// diagonal per row).
Eigen::MatrixXd DescriptorFunctionalMap(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                                        const Eigen::VectorXd& evals_s,
                                        const Eigen::VectorXd& evals_t, double mu);

struct DescriptorAgreement {
  std::array<double, 4> agreement{};  // per candidate, in [-1, 1]
  std::vector<int> map;               // target vertex of each source sample
};

// Per candidate k (CandidateRotations(), diagonal): with c_a the normalised correlation
//   c_a = sum_i Ys(i, a) Yt(T(i), a) / sqrt(sum_i Ys(i, a)^2 sum_i Yt(T(i), a)^2)
// along in-plane axis a over the source samples i, T the point map of the descriptor functional
// map, the agreement is R_k(1, 1) c_1 (axes = 1) or (R_k(1, 1) c_1 + R_k(2, 2) c_2) / 2
// (axes = 2). Ys, Yt: canonical embeddings; bases with at least options.eigenpairs eigenpairs;
// source_products, target_products: ComputeWksProducts(basis, options.k, options.eigenpairs)
// of each shape (per-shape data of the flip stage); samples: source vertex ids (the first
// options.samples are used). Throws ConfigError for invalid options and InvalidInputError for
// inconsistent inputs.
DescriptorAgreement DescriptorMapAgreement(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                           const LaplaceBasis& source, const LaplaceBasis& target,
                                           const WksProducts& source_products,
                                           const WksProducts& target_products,
                                           const std::vector<int>& samples,
                                           const DescriptorMapOptions& options);

}  // namespace symembed

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

#include "core/fmap/descriptors.h"
#include "core/range.h"
#include "core/spectral.h"

namespace symembed {

struct DescriptorMapOptions {
  int k = 30;  // basis size of the functional map (both bases need `eigenpairs`)
  static constexpr Range kK = Range::Closed(2, 1000);
  int eigenpairs = 60;  // eigenpairs the wave kernel signatures are built from (>= k)
  static constexpr Range kEigenpairs = Range::Closed(2, 1000);
  int energies = 100;  // number of wave kernel signature energies
  static constexpr Range kEnergies = Range::Closed(1, 10000);
  double sigma = 7.0;  // energy bandwidth in units of the energy spacing [Aubry et al. 2011]
  static constexpr Range kSigma = Range::Above(0.0);
  double mu = 1e-2;  // weight of the commutativity term, relative (see DescriptorFunctionalMap)
  static constexpr Range kMu = Range::AtLeast(0.0);
  int samples = 300;  // source samples the point map is computed on
  static constexpr Range kSamples = Range::Closed(1, 100000);
  // In-plane axes compared: 1 (the first in-plane axis of the canonical frame only) or 2 (both).
  int axes = 1;
  static constexpr Range kAxes = Range::Closed(1, 2);

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("k", self.k, kK);
    visit("eigenpairs", self.eigenpairs, kEigenpairs);
    visit("energies", self.energies, kEnergies);
    visit("sigma", self.sigma, kSigma);
    visit("mu", self.mu, kMu);
    visit("samples", self.samples, kSamples);
    visit("axes", self.axes, kAxes);
  }
  bool IsValid(std::string* error) const;
};

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

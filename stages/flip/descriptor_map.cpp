#include "stages/flip/descriptor_map.h"

#include <cmath>

#include "core/errors.h"
#include "core/fmap/functional_map.h"
#include "registry/types.h"

namespace symembed {

bool DescriptorMapOptions::IsValid(std::string* error) const {
  std::string why = FieldViolation(*this);
  if (why.empty() && eigenpairs < k) {
    why = "eigenpairs must be >= k (" + std::to_string(k) + "), got " + std::to_string(eigenpairs);
  }
  return NoViolation(why, error);
}

DescriptorAgreement DescriptorMapAgreement(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                           const LaplaceBasis& source, const LaplaceBasis& target,
                                           const WksProducts& source_products,
                                           const WksProducts& target_products,
                                           const std::vector<int>& samples,
                                           const DescriptorMapOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("flip descriptor: " + error);
  if (source.NumEigenpairs() < options.eigenpairs || target.NumEigenpairs() < options.eigenpairs) {
    throw InvalidInputError("flip descriptor: the bases hold fewer than " +
                            std::to_string(options.eigenpairs) + " eigenpairs");
  }
  if (source.NumVertices() != Ys.rows() || target.NumVertices() != Yt.rows()) {
    throw InvalidInputError("flip descriptor: Laplace-Beltrami bases do not match the embeddings");
  }
  if (samples.empty()) throw InvalidInputError("flip descriptor: no source samples");
  // The first options.eigenpairs of each basis, without copying them.
  const int n = options.eigenpairs;
  double sigma = 0.0;
  const Eigen::VectorXd energies = WksEnergies(source.evals.head(n), target.evals.head(n),
                                               options.energies, options.sigma, &sigma);
  for (const WksProducts* products : {&source_products, &target_products}) {
    if (products->P.rows() != options.k || products->P.cols() != n) {
      throw InvalidInputError("flip descriptor: the signature products are " +
                              std::to_string(products->P.rows()) + " x " +
                              std::to_string(products->P.cols()) + ", not k x eigenpairs");
    }
  }
  const Eigen::MatrixXd A =
      WksCoefficients(source_products, EnergyWeights(source.evals.head(n), energies, sigma));
  const Eigen::MatrixXd B =
      WksCoefficients(target_products, EnergyWeights(target.evals.head(n), energies, sigma));
  const Eigen::MatrixXd C =
      DescriptorFunctionalMap(A, B, source.evals, target.evals, options.mu);

  const std::vector<int> ids(samples.begin(),
                             samples.begin() + std::min<size_t>(samples.size(), options.samples));
  DescriptorAgreement out;
  out.map = PointMapFromFunctionalMap(source.evecs.leftCols(options.k),
                                      target.evecs.leftCols(options.k), target.mass, C, ids);
  // Normalised correlation per in-plane axis, so that a thin axis (front-back of a human) weighs
  // as much as a long one.
  Eigen::Vector2d cross = Eigen::Vector2d::Zero(), ss = cross, tt = cross;
  for (size_t r = 0; r < ids.size(); ++r) {
    const int i = ids[r], j = out.map[r];
    for (int a = 1; a <= 2; ++a) {
      cross(a - 1) += Ys(i, a) * Yt(j, a);
      ss(a - 1) += Ys(i, a) * Ys(i, a);
      tt(a - 1) += Yt(j, a) * Yt(j, a);
    }
  }
  Eigen::Vector2d corr = Eigen::Vector2d::Zero();
  for (int a = 0; a < 2; ++a) {
    const double norm = std::sqrt(ss(a) * tt(a));
    if (norm > 0.0) corr(a) = cross(a) / norm;
  }
  const auto rotations = CandidateRotations();
  for (int c = 0; c < 4; ++c) {
    out.agreement[c] = options.axes == 1
                           ? rotations[c](1, 1) * corr(0)
                           : 0.5 * (rotations[c](1, 1) * corr(0) + rotations[c](2, 2) * corr(1));
  }
  return out;
}

}  // namespace symembed

#include "stages/flip/hks.h"

#include <algorithm>
#include <cmath>

#include "core/errors.h"
#include "stages/flip/flip_common.h"

namespace symembed {

Eigen::MatrixXd HeatKernelSignature(const LaplaceBasis& basis, const Eigen::VectorXd& times) {
  const Eigen::MatrixXd phi2 = basis.evecs.array().square().matrix();
  // E(i, t) = exp(-lambda_i t); eigenvalues ~0 (clamped at 0) keep weight 1.
  Eigen::MatrixXd E(basis.NumEigenpairs(), times.size());
  for (int i = 0; i < basis.NumEigenpairs(); ++i) {
    for (int t = 0; t < times.size(); ++t) {
      E(i, t) = std::exp(-std::max(basis.evals(i), 0.0) * times(t));
    }
  }
  Eigen::MatrixXd H = phi2 * E;
  const Eigen::RowVectorXd trace = E.colwise().sum();
  return H.array().rowwise() / trace.array();
}

Eigen::VectorXd HksTimes(const LaplaceBasis& a, const LaplaceBasis& b, int num_times) {
  double a1, amax, b1, bmax;
  PositiveEigenvalueRange(a.evals, &a1, &amax);
  PositiveEigenvalueRange(b.evals, &b1, &bmax);
  const double lambda_1 = 0.5 * (a1 + b1), lambda_max = 0.5 * (amax + bmax);
  if (!(lambda_1 > 0.0) || !(lambda_max > 0.0)) {
    throw InvalidInputError("flip hks: no positive Laplace-Beltrami eigenvalue");
  }
  const double t_min = 4.0 * std::log(10.0) / lambda_max, t_max = 4.0 * std::log(10.0) / lambda_1;
  Eigen::VectorXd times(num_times);
  for (int k = 0; k < num_times; ++k) {
    const double f = num_times == 1 ? 0.5 : static_cast<double>(k) / (num_times - 1);
    times(k) = std::exp(std::log(t_min) + f * (std::log(t_max) - std::log(t_min)));
  }
  return times;
}

std::array<double, 4> HksFlipScores(const Eigen::MatrixX3d& Ys, const Eigen::MatrixX3d& Yt,
                                    const LaplaceBasis& source, const LaplaceBasis& target,
                                    const HksFlipOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("flip hks: " + error);
  if (source.NumVertices() != Ys.rows() || target.NumVertices() != Yt.rows()) {
    throw InvalidInputError("flip hks: Laplace-Beltrami bases do not match the embeddings");
  }
  const Eigen::VectorXd times = HksTimes(source, target, options.num_times);
  // Floor before the log: vertices without mass have zero eigenvector rows.
  auto log_hks = [&](const LaplaceBasis& b) {
    return Eigen::MatrixXd(HeatKernelSignature(b, times).array().max(1e-12).log());
  };
  const Eigen::MatrixXd hs = log_hks(source), ht = log_hks(target);
  const Eigen::VectorXd as = source.mass / std::max(source.mass.sum(), 1e-300);
  const CandidateMaps maps = ComputeCandidateMaps(Ys, Yt, options.threads);
  std::array<double, 4> scores{};
  for (int k = 0; k < 4; ++k) {
    double sum = 0.0;
    for (int v = 0; v < Ys.rows(); ++v) {
      sum += as(v) * (hs.row(v) - ht.row(maps.map[k][v])).cwiseAbs().mean();
    }
    scores[k] = sum;
  }
  return scores;
}

}  // namespace symembed

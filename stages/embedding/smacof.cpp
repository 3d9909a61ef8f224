#include "stages/embedding/smacof.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.h"
#include "core/parallel.h"

namespace symembed {

bool SmacofOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (!(tolerance >= 0.0)) why << "tolerance must be >= 0, got " << tolerance;
  else if (max_iterations < 0) why << "max_iterations must be >= 0, got " << max_iterations;
  else if (!(weight_power >= 0.0 && weight_power <= 8.0))
    why << "weight_power must be in [0, 8], got " << weight_power;
  else if (!(relaxation >= 1.0 && relaxation < 2.0))
    why << "relaxation must be in [1, 2), got " << relaxation;
  else if (threads < 0) why << "threads must be >= 0, got " << threads;
  if (why.str().empty()) return true;
  if (error) *error = why.str();
  return false;
}

namespace {

constexpr int kRowBlock = 32;

// One pass over all ordered pairs: the distances of X, the (weighted) stress and, when BX is
// given, B(X) X with b_ij = -w_ij d_ij / ||x_i - x_j|| (0 for coincident points), b_ii =
// -sum_j b_ij. Rows are independent, so blocks of rows run in parallel; the stress is summed
// per block in a fixed order so the result does not depend on the thread count.
double StressPass(const Eigen::MatrixXd& D, const Eigen::MatrixXd* W, const Eigen::MatrixXd& X,
                  Eigen::MatrixXd* BX, int threads) {
  const int n = static_cast<int>(D.rows());
  const int dims = static_cast<int>(X.cols());
  const int blocks = (n + kRowBlock - 1) / kRowBlock;
  std::vector<double> partial(blocks, 0.0);
  ParallelFor(
      blocks,
      [&](int b) {
        Eigen::ArrayXd dist(n), ratio(n);
        double sum = 0.0;
        const int end = std::min(n, (b + 1) * kRowBlock);
        for (int i = b * kRowBlock; i < end; ++i) {
          dist = (X.col(0).array() - X(i, 0)).square();
          for (int c = 1; c < dims; ++c) dist += (X.col(c).array() - X(i, c)).square();
          dist = dist.sqrt();
          const auto Di = D.col(i).array();
          if (W != nullptr) {
            const auto Wi = W->col(i).array();
            sum += (Wi * (Di - dist).square()).sum();
            if (BX != nullptr) ratio = (dist > 0.0).select(Wi * Di / dist, 0.0);
          } else {
            sum += (Di - dist).square().sum();
            if (BX != nullptr) ratio = (dist > 0.0).select(Di / dist, 0.0);
          }
          if (BX != nullptr) {
            const double ratio_sum = ratio.sum();
            for (int c = 0; c < dims; ++c) {
              (*BX)(i, c) = X(i, c) * ratio_sum - ratio.matrix().dot(X.col(c));
            }
          }
        }
        partial[b] = sum;
      },
      threads);
  double total = 0.0;
  for (double p : partial) total += p;
  return 0.5 * total;  // each unordered pair was visited twice
}

void CheckDistances(const Eigen::MatrixXd& D, const char* who) {
  if (D.rows() != D.cols()) {
    std::ostringstream m;
    m << who << ": distance matrix is " << D.rows() << "x" << D.cols() << ", expected square";
    throw InvalidInputError(m.str());
  }
  if (!D.allFinite() || (D.array() < 0.0).any()) {
    throw InvalidInputError(std::string(who) + ": distances must be finite and non-negative");
  }
}

}  // namespace

double RawStress(const Eigen::MatrixXd& D, const Eigen::MatrixXd& X, int threads) {
  CheckDistances(D, "RawStress");
  SYMEMBED_CHECK(X.rows() == D.rows() && X.cols() >= 1, "RawStress: X is " << X.rows() << "x"
                                                          << X.cols() << ", D is " << D.rows());
  return StressPass(D, nullptr, X, nullptr, threads);
}

double NormalizedStress(const Eigen::MatrixXd& D, const Eigen::MatrixXd& X, int threads) {
  const double eta2 = 0.5 * D.squaredNorm();
  return eta2 > 0.0 ? std::sqrt(RawStress(D, X, threads) / eta2) : 0.0;
}

Eigen::MatrixXd ScaleToDistances(const Eigen::MatrixXd& D, const Eigen::MatrixXd& X) {
  CheckDistances(D, "ScaleToDistances");
  SYMEMBED_CHECK(X.rows() == D.rows(), "ScaleToDistances: X has " << X.rows() << " rows, D "
                                                                   << D.rows());
  const Eigen::MatrixXd Xc = X.rowwise() - X.colwise().mean();
  const int n = static_cast<int>(X.rows());
  // s = sum d_ij e_ij / sum e_ij^2 over ordered pairs (the factor 2 cancels).
  double de = 0.0, ee = 0.0;
  for (int i = 0; i < n; ++i) {
    const Eigen::ArrayXd e = (Xc.rowwise() - Xc.row(i)).rowwise().norm().array();
    de += (e * D.col(i).array()).sum();
    ee += e.square().sum();
  }
  return ee > 0.0 ? (Xc * (de / ee)).eval() : Xc;
}

SmacofResult Smacof(const Eigen::MatrixXd& D_in, const Eigen::MatrixXd& init,
                    const SmacofOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw ConfigError("SmacofOptions: " + why);
  CheckDistances(D_in, "Smacof");
  const int n = static_cast<int>(D_in.rows());
  if (init.rows() != n || init.cols() < 1 || !init.allFinite()) {
    std::ostringstream m;
    m << "Smacof: init is " << init.rows() << "x" << init.cols() << " (finite expected), D is "
      << n << "x" << n;
    throw InvalidInputError(m.str());
  }
  const Eigen::MatrixXd D = 0.5 * (D_in + D_in.transpose());
  const double eta2 = 0.5 * D.squaredNorm();
  const int threads = options.threads;

  // Weighted path: W and the factorisation of V + 11^T/n, whose inverse applied to the centred
  // B(X) X equals V^+ B(X) X (V 1 = 0, so adding 11^T/n only fixes the null space).
  const bool weighted = options.weight_power > 0.0;
  Eigen::MatrixXd W;
  Eigen::LLT<Eigen::MatrixXd> v_factor;
  if (weighted) {
    W = (D.array() > 0.0).select(D.array().pow(-options.weight_power), 0.0).matrix();
    Eigen::MatrixXd Vm = -W;
    Vm.diagonal() = W.rowwise().sum();
    Vm.array() += 1.0 / n;
    v_factor.compute(Vm);
    if (v_factor.info() != Eigen::Success) {
      throw InvalidInputError("Smacof: the weight graph is disconnected (V + 11^T/n singular)");
    }
  }
  const Eigen::MatrixXd* Wp = weighted ? &W : nullptr;
  auto guttman = [&](const Eigen::MatrixXd& BX) -> Eigen::MatrixXd {
    return weighted ? v_factor.solve(BX).eval() : (BX / static_cast<double>(n)).eval();
  };

  SmacofResult result;
  Eigen::MatrixXd X = init.rowwise() - init.colwise().mean();
  Eigen::MatrixXd BX(n, X.cols()), BX_next(n, X.cols());
  double sigma = StressPass(D, Wp, X, &BX, threads);
  result.stress_history.push_back(sigma);
  // Below this the configuration reproduces D to rounding; relative changes are then noise.
  const double floor = 1e-24 * (weighted ? (W.array() * D.array().square()).sum() : eta2);

  for (int it = 0; it < options.max_iterations; ++it) {
    if (sigma <= floor) {
      result.converged = true;
      break;
    }
    const Eigen::MatrixXd G = guttman(BX);
    Eigen::MatrixXd X_next = X + options.relaxation * (G - X);
    double sigma_next = StressPass(D, Wp, X_next, &BX_next, threads);
    if (sigma_next > sigma && options.relaxation != 1.0) {
      X_next = G;
      sigma_next = StressPass(D, Wp, X_next, &BX_next, threads);
    }
    if (sigma_next > sigma) {
      // Even the plain Guttman step went up: only rounding is left, keep the previous iterate.
      result.converged = true;
      break;
    }
    const double change = (sigma - sigma_next) / sigma;
    X.swap(X_next);
    BX.swap(BX_next);
    sigma = sigma_next;
    result.stress_history.push_back(sigma);
    result.iterations = it + 1;
    if (change < options.tolerance) {
      result.converged = true;
      break;
    }
  }
  if (!result.converged && sigma <= floor) result.converged = true;
  result.X = X.rowwise() - X.colwise().mean();
  result.stress = sigma;
  const double raw = weighted ? StressPass(D, nullptr, result.X, nullptr, threads) : sigma;
  result.normalized_stress = eta2 > 0.0 ? std::sqrt(raw / eta2) : 0.0;
  return result;
}

}  // namespace symembed

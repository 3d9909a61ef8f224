#include "stages/embedding/smacof.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>

#include "core/errors.h"
#include "core/parallel.h"

namespace symembed {

bool SmacofOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (!(tolerance >= 0.0))
    why << "tolerance must be >= 0, got " << tolerance;
  else if (max_iterations < 0)
    why << "max_iterations must be >= 0, got " << max_iterations;
  else if (!(weight_power >= 0.0 && weight_power <= 8.0))
    why << "weight_power must be in [0, 8], got " << weight_power;
  else if (!(relaxation >= 1.0 && relaxation < 2.0))
    why << "relaxation must be in [1, 2), got " << relaxation;
  else if (anderson_window < 0 || anderson_window > 20)
    why << "anderson_window must be in [0, 20], got " << anderson_window;
  else if (threads < 0)
    why << "threads must be >= 0, got " << threads;
  if (why.str().empty()) return true;
  if (error) *error = why.str();
  return false;
}

namespace {

// The pairs are split over a fixed number of lanes, each with its own accumulators, so the
// summation order (and the result) does not depend on the thread count.
constexpr int kLanes = 16;
constexpr int kRowBlock = 8;

// One pass over the unordered pairs i < j: the distances of X, the (weighted) stress and, when
// BX is given, B(X) X with b_ij = -w_ij d_ij / ||x_i - x_j|| (0 for coincident points), b_ii =
// -sum_j b_ij, i.e. (B(X) X)_i = sum_j w_ij d_ij / ||x_i - x_j|| (x_i - x_j). Each pair's square
// root and division are done once and its contribution added to both rows. Row i only reads
// the contiguous tails j > i of the columns of X and of column i of D (D is symmetric).
double StressPass(const Eigen::MatrixXd& D, const Eigen::MatrixXd* W, const Eigen::MatrixXd& X,
                  Eigen::MatrixXd* BX, int threads) {
  const int n = static_cast<int>(D.rows());
  const int dims = static_cast<int>(X.cols());
  const int blocks = (n + kRowBlock - 1) / kRowBlock;
  std::vector<double> lane_stress(kLanes, 0.0);
  std::vector<Eigen::MatrixXd> lane_bx(BX != nullptr ? kLanes : 0);
  ParallelFor(
      kLanes,
      [&](int lane) {
        Eigen::ArrayXd dist(n), ratio(n);
        Eigen::ArrayXXd diff(n, dims);
        Eigen::MatrixXd* acc = nullptr;
        if (BX != nullptr) {
          lane_bx[lane].setZero(n, dims);
          acc = &lane_bx[lane];
        }
        double sum = 0.0;
        // Blocks are dealt round-robin so every lane gets long and short rows alike.
        for (int b = lane; b < blocks; b += kLanes) {
          const int end = std::min(n, (b + 1) * kRowBlock);
          for (int i = b * kRowBlock; i < end; ++i) {
            const int len = n - i - 1;
            if (len == 0) continue;
            auto dx = diff.topRows(len);
            auto di = dist.head(len);
            for (int c = 0; c < dims; ++c) {
              dx.col(c) = X.col(c).segment(i + 1, len).array() - X(i, c);
            }
            di = dx.square().rowwise().sum().sqrt();
            const auto Dt = D.col(i).segment(i + 1, len).array();
            auto ri = ratio.head(len);
            if (W != nullptr) {
              const auto Wt = W->col(i).segment(i + 1, len).array();
              sum += (Wt * (Dt - di).square()).sum();
              if (acc != nullptr) ri = (di > 0.0).select(Wt * Dt / di, 0.0);
            } else {
              sum += (Dt - di).square().sum();
              if (acc != nullptr) ri = (di > 0.0).select(Dt / di, 0.0);
            }
            if (acc != nullptr) {
              for (int c = 0; c < dims; ++c) {
                // x_i - x_j = -dx for row i; x_j - x_i = dx for the rows j.
                (*acc)(i, c) -= (ri * dx.col(c)).sum();
                acc->col(c).segment(i + 1, len).array() += ri * dx.col(c);
              }
            }
          }
        }
        lane_stress[lane] = sum;
      },
      threads);
  double total = 0.0;
  for (double s : lane_stress) total += s;
  if (BX != nullptr) {
    BX->setZero(n, dims);
    for (const Eigen::MatrixXd& a : lane_bx) *BX += a;
  }
  return total;
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

// Anderson acceleration (type II) of the fixed-point map X -> G(X): from the last m iterates
// x_i with images g_i and residuals f_i = g_i - x_i, the next candidate is g_k - dG theta with
// theta = argmin ||f_k - dF theta||, dG, dF the columns g_{i+1} - g_i, f_{i+1} - f_i.
// [Walker & Ni 2011] Anderson acceleration for fixed-point iterations.
// [Peng et al. 2018] Anderson acceleration for geometry optimization and physics simulation.
class Anderson {
 public:
  explicit Anderson(int window) : window_(window) {}
  void Reset() {
    dg_.clear();
    df_.clear();
    has_last_ = false;
  }
  // Records the iterate x with image g.
  void Push(const Eigen::MatrixXd& x, const Eigen::MatrixXd& g) {
    Eigen::MatrixXd f = g - x;
    if (has_last_) {
      dg_.push_back(g - last_g_);
      df_.push_back(f - last_f_);
      if (static_cast<int>(dg_.size()) > window_) {
        dg_.pop_front();
        df_.pop_front();
      }
    }
    last_g_ = g;
    last_f_ = std::move(f);
    has_last_ = true;
  }
  bool Ready() const { return !dg_.empty(); }
  Eigen::MatrixXd Candidate() const {
    const int m = static_cast<int>(df_.size());
    const Eigen::Index size = last_f_.size();
    Eigen::MatrixXd F(size, m);
    for (int j = 0; j < m; ++j) F.col(j) = Eigen::Map<const Eigen::VectorXd>(df_[j].data(), size);
    const Eigen::Map<const Eigen::VectorXd> f(last_f_.data(), size);
    const Eigen::VectorXd theta = F.colPivHouseholderQr().solve(f);
    Eigen::MatrixXd x = last_g_;
    for (int j = 0; j < m; ++j) x -= theta(j) * dg_[j];
    return x;
  }

 private:
  int window_;
  std::deque<Eigen::MatrixXd> dg_, df_;
  Eigen::MatrixXd last_g_, last_f_;
  bool has_last_ = false;
};

}  // namespace

double RawStress(const Eigen::MatrixXd& D, const Eigen::MatrixXd& X, int threads) {
  CheckDistances(D, "RawStress");
  SYMEMBED_CHECK(X.rows() == D.rows() && X.cols() >= 1,
                 "RawStress: X is " << X.rows() << "x" << X.cols() << ", D is " << D.rows());
  const Eigen::MatrixXd S = 0.5 * (D + D.transpose());
  return StressPass(S, nullptr, X, nullptr, threads);
}

double NormalizedStress(const Eigen::MatrixXd& D, const Eigen::MatrixXd& X, int threads) {
  const double eta2 = 0.5 * D.squaredNorm();
  return eta2 > 0.0 ? std::sqrt(RawStress(D, X, threads) / eta2) : 0.0;
}

Eigen::MatrixXd ScaleToDistances(const Eigen::MatrixXd& D, const Eigen::MatrixXd& X) {
  CheckDistances(D, "ScaleToDistances");
  SYMEMBED_CHECK(X.rows() == D.rows(),
                 "ScaleToDistances: X has " << X.rows() << " rows, D " << D.rows());
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
    m << "Smacof: init is " << init.rows() << "x" << init.cols() << " (finite expected), D is " << n
      << "x" << n;
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
  int evaluations = 0;
  auto pass = [&](const Eigen::MatrixXd& Y, Eigen::MatrixXd* BY) {
    ++evaluations;
    return StressPass(D, Wp, Y, BY, threads);
  };
  double sigma = pass(X, &BX);
  result.stress_history.push_back(sigma);
  // Below this the configuration reproduces D to rounding; relative changes are then noise.
  const double floor = 1e-24 * (weighted ? 0.5 * (W.array() * D.array().square()).sum() : eta2);

  Anderson anderson(options.anderson_window);
  Eigen::MatrixXd G = guttman(BX);
  if (options.anderson_window > 0) anderson.Push(X, G);
  bool force_plain = false;  // after an accelerated step changed stress by less than tolerance
  for (int it = 0; it < options.max_iterations; ++it) {
    if (sigma <= floor) {
      result.converged = true;
      break;
    }
    // Candidates in order of preference; each must lower stress, the last never raises it in
    // exact arithmetic (plain Guttman step).
    bool accelerated = false;
    Eigen::MatrixXd X_next;
    double sigma_next = sigma;
    bool accepted = false;
    if (!force_plain && anderson.Ready()) {
      X_next = anderson.Candidate();
      sigma_next = pass(X_next, &BX_next);
      accepted = sigma_next < sigma;
      accelerated = accepted;
      if (!accepted) anderson.Reset();
    }
    if (!accepted && options.relaxation != 1.0) {
      X_next = X + options.relaxation * (G - X);
      sigma_next = pass(X_next, &BX_next);
      accepted = sigma_next <= sigma;
    }
    if (!accepted) {
      X_next = G;
      sigma_next = pass(X_next, &BX_next);
      accepted = sigma_next <= sigma;
    }
    if (!accepted) {
      // Even the plain Guttman step went up: only rounding is left, keep the previous iterate.
      result.converged = true;
      break;
    }
    const double change = (sigma - sigma_next) / sigma;
    X.swap(X_next);
    BX.swap(BX_next);
    sigma = sigma_next;
    G = guttman(BX);
    if (options.anderson_window > 0) anderson.Push(X, G);
    result.stress_history.push_back(sigma);
    result.iterations = it + 1;
    force_plain = false;
    if (change < options.tolerance) {
      // An accelerated step can stall while plain steps still make progress: confirm with one.
      if (!accelerated) {
        result.converged = true;
        break;
      }
      force_plain = true;
    }
  }
  if (!result.converged && sigma <= floor) result.converged = true;
  result.X = X.rowwise() - X.colwise().mean();
  result.stress = sigma;
  result.evaluations = evaluations;
  const double raw = weighted ? StressPass(D, nullptr, result.X, nullptr, threads) : sigma;
  result.normalized_stress = eta2 > 0.0 ? std::sqrt(raw / eta2) : 0.0;
  return result;
}

}  // namespace symembed

#include "core/mds/smacof.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <deque>
#include <sstream>

#include "core/errors.h"
#include "core/mds/stress_pass.h"

namespace symembed {

bool SmacofOptions::IsValid(std::string* error) const {
  std::string why = FieldViolation(*this);
  if (why.empty()) why = FirstViolation({{"threads", kThreads, threads}});
  return NoViolation(why, error);
}

namespace {

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

namespace {

// The Guttman transform X -> V^+ B(X) X of the stress of D. Weighted (w_ij = d_ij^-weight_power),
// V^+ is applied through the factorisation of V + 11^T/n, whose inverse applied to the centred
// B(X) X equals V^+ B(X) X (V 1 = 0, so adding 11^T/n only fixes the null space); unweighted, it
// is B(X) X / n.
class GuttmanTransform {
 public:
  // Throws InvalidInputError when the weight graph is disconnected.
  GuttmanTransform(const Eigen::MatrixXd& D, double weight_power)
      : n_(static_cast<int>(D.rows())), weighted_(weight_power > 0.0) {
    if (!weighted_) return;
    W_ = (D.array() > 0.0).select(D.array().pow(-weight_power), 0.0).matrix();
    Eigen::MatrixXd Vm = -W_;
    Vm.diagonal() = W_.rowwise().sum();
    Vm.array() += 1.0 / n_;
    v_factor_.compute(Vm);
    if (v_factor_.info() != Eigen::Success) {
      throw InvalidInputError("Smacof: the weight graph is disconnected (V + 11^T/n singular)");
    }
  }
  bool weighted() const { return weighted_; }
  // The weights, or null when unweighted (StressPass).
  const Eigen::MatrixXd* weights() const { return weighted_ ? &W_ : nullptr; }
  Eigen::MatrixXd operator()(const Eigen::MatrixXd& BX) const {
    return weighted_ ? v_factor_.solve(BX).eval() : (BX / static_cast<double>(n_)).eval();
  }

 private:
  int n_;
  bool weighted_;
  Eigen::MatrixXd W_;
  Eigen::LLT<Eigen::MatrixXd> v_factor_;
};

// A step of SMACOF from X (stress sigma, Guttman transform G): the candidates in order of
// preference, each kept only if it does not raise stress, the accelerated one only if it lowers
// it: Anderson's (unless force_plain), the relaxed step X + relaxation (G - X), the plain step
// G, which never raises stress in exact arithmetic. pass(Y, &BY) is the stress of Y and B(Y) Y.
struct SmacofStep {
  bool accepted = false;
  bool accelerated = false;
  Eigen::MatrixXd X;
  double sigma = 0.0;
};

template <typename Pass>
SmacofStep NextSmacofStep(const Eigen::MatrixXd& X, const Eigen::MatrixXd& G, double sigma,
                          const SmacofOptions& options, bool force_plain, Anderson* anderson,
                          Eigen::MatrixXd* BX_next, Pass pass) {
  SmacofStep step;
  step.sigma = sigma;
  if (!force_plain && anderson->Ready()) {
    step.X = anderson->Candidate();
    step.sigma = pass(step.X, BX_next);
    step.accepted = step.sigma < sigma;
    step.accelerated = step.accepted;
    if (!step.accepted) anderson->Reset();
  }
  if (!step.accepted && options.relaxation != 1.0) {
    step.X = X + options.relaxation * (G - X);
    step.sigma = pass(step.X, BX_next);
    step.accepted = step.sigma <= sigma;
  }
  if (!step.accepted) {
    step.X = G;
    step.sigma = pass(step.X, BX_next);
    step.accepted = step.sigma <= sigma;
  }
  return step;
}

// The checks of Smacof's inputs.
void CheckSmacofInputs(const Eigen::MatrixXd& D, const Eigen::MatrixXd& init,
                       const SmacofOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw ConfigError("SmacofOptions: " + why);
  CheckDistances(D, "Smacof");
  const int n = static_cast<int>(D.rows());
  if (init.rows() != n || init.cols() < 1 || !init.allFinite()) {
    std::ostringstream m;
    m << "Smacof: init is " << init.rows() << "x" << init.cols() << " (finite expected), D is " << n
      << "x" << n;
    throw InvalidInputError(m.str());
  }
}

}  // namespace

SmacofResult Smacof(const Eigen::MatrixXd& D_in, const Eigen::MatrixXd& init,
                    const SmacofOptions& options) {
  CheckSmacofInputs(D_in, init, options);
  const int n = static_cast<int>(D_in.rows());
  const Eigen::MatrixXd D = 0.5 * (D_in + D_in.transpose());
  const double eta2 = 0.5 * D.squaredNorm();
  const int threads = options.threads;
  const GuttmanTransform guttman(D, options.weight_power);
  const bool weighted = guttman.weighted();

  SmacofResult result;
  Eigen::MatrixXd X = init.rowwise() - init.colwise().mean();
  Eigen::MatrixXd BX(n, X.cols()), BX_next(n, X.cols());
  int evaluations = 0;
  auto pass = [&](const Eigen::MatrixXd& Y, Eigen::MatrixXd* BY) {
    ++evaluations;
    return StressPass(D, guttman.weights(), Y, BY, threads);
  };
  double sigma = pass(X, &BX);
  result.stress_history.push_back(sigma);
  // Below this the configuration reproduces D to rounding; relative changes are then noise.
  const double floor =
      1e-24 *
      (weighted ? 0.5 * (guttman.weights()->array() * D.array().square()).sum() : eta2);

  Anderson anderson(options.anderson_window);
  Eigen::MatrixXd G = guttman(BX);
  if (options.anderson_window > 0) anderson.Push(X, G);
  bool force_plain = false;  // after an accelerated step changed stress by less than tolerance
  for (int it = 0; it < options.max_iterations; ++it) {
    if (sigma <= floor) {
      result.converged = true;
      break;
    }
    SmacofStep step = NextSmacofStep(X, G, sigma, options, force_plain, &anderson, &BX_next, pass);
    if (!step.accepted) {
      // Even the plain Guttman step went up: only rounding is left, keep the previous iterate.
      result.converged = true;
      break;
    }
    const double change = (sigma - step.sigma) / sigma;
    X.swap(step.X);
    BX.swap(BX_next);
    sigma = step.sigma;
    G = guttman(BX);
    if (options.anderson_window > 0) anderson.Push(X, G);
    result.stress_history.push_back(sigma);
    result.iterations = it + 1;
    force_plain = false;
    if (change < options.tolerance) {
      // An accelerated step can stall while plain steps still make progress: confirm with one.
      if (!step.accelerated) {
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

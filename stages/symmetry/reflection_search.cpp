#include "stages/symmetry/reflection_search.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "core/errors.h"
#include "core/procrustes.h"

namespace symembed {

bool ReflectionSearchOptions::IsValid(std::string* error) const {
  std::string why = FieldViolation(*this);
  if (why.empty()) why = FirstViolation({{"tolerance", kTolerance, tolerance}});
  return NoViolation(why, error);
}

Eigen::MatrixXd Reflect(const Eigen::MatrixXd& P, const Eigen::VectorXd& normal, double offset) {
  const Eigen::VectorXd s = (P * normal).array() - offset;
  return P - 2.0 * s * normal.transpose();
}

bool FitReflection(const Eigen::MatrixXd& P, const std::vector<int>& sigma,
                   const Eigen::VectorXd& w, Eigen::VectorXd* normal, double* offset) {
  const int d = static_cast<int>(P.cols());
  Eigen::MatrixXd scatter = Eigen::MatrixXd::Zero(d, d);
  Eigen::VectorXd mid_sum = Eigen::VectorXd::Zero(d);
  double w_sum = 0.0;
  // Element by element, without temporaries: scatter += (w_i (a - b)) (a - b)^T and
  // mid_sum += (w_i / 2) (a + b) for a = P_i, b = P_sigma(i).
  for (int i = 0; i < P.rows(); ++i) {
    const double wi = w(i);
    if (wi <= 0.0) continue;
    for (int r = 0; r < d; ++r) {
      const double diff_r = P(i, r) - P(sigma[i], r);
      for (int c = 0; c < d; ++c) scatter(r, c) += (wi * diff_r) * (P(i, c) - P(sigma[i], c));
      mid_sum(r) += (wi * 0.5) * (P(i, r) + P(sigma[i], r));
    }
    w_sum += wi;
  }
  if (w_sum <= 0.0 || scatter.trace() <= 0.0) return false;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(scatter);
  Eigen::VectorXd n = eig.eigenvectors().col(d - 1);
  // Keep the orientation of the previous normal so that iterates are comparable.
  if (normal->size() == d && n.dot(*normal) < 0.0) n = -n;
  *normal = n;
  *offset = n.dot(mid_sum / w_sum);
  return true;
}

namespace {

// Residual value at the trim_fraction quantile.
double TrimThreshold(const Eigen::VectorXd& r, double trim_fraction) {
  std::vector<double> sorted(r.data(), r.data() + r.size());
  const size_t keep = std::max<size_t>(1, static_cast<size_t>(std::ceil(trim_fraction * sorted.size())));
  std::nth_element(sorted.begin(), sorted.begin() + (keep - 1), sorted.end());
  return sorted[keep - 1];
}

void Score(const Eigen::MatrixXd& P, const KnnIndex& index, double size,
           const ReflectionSearchOptions& options, ReflectionFit* fit) {
  const Eigen::MatrixXd Q = Reflect(P, fit->normal, fit->offset);
  fit->sigma = index.Nearest(Q, &fit->residual, 1);
  fit->fixed_fraction = FixedFraction(fit->sigma);
  fit->score = TruncatedScore(fit->residual, size, options.outlier_distance);
  if (fit->fixed_fraction > options.max_fixed_fraction) {
    fit->score = std::numeric_limits<double>::infinity();
  }
}

}  // namespace

double FixedFraction(const std::vector<int>& sigma) {
  if (sigma.empty()) return 0.0;
  int fixed = 0;
  for (size_t i = 0; i < sigma.size(); ++i) fixed += sigma[i] == static_cast<int>(i);
  return static_cast<double>(fixed) / sigma.size();
}

double TruncatedScore(const Eigen::VectorXd& residual, double size, double outlier_distance) {
  const double s = std::max(size, std::numeric_limits<double>::min());
  return residual.array().min(outlier_distance * s).mean() / s;
}

ReflectionFit EvaluateReflection(const Eigen::MatrixXd& P, const KnnIndex& index,
                                 const Eigen::VectorXd& normal, double offset,
                                 const ReflectionSearchOptions& options) {
  ReflectionFit fit;
  fit.normal = normal.normalized();
  fit.offset = offset;
  Score(P, index, RmsRadius(P), options, &fit);
  return fit;
}

ReflectionFit RefineReflection(const Eigen::MatrixXd& P, const KnnIndex& index,
                               const Eigen::VectorXd& normal, double offset,
                               const ReflectionSearchOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("reflection search: " + error);
  SYMEMBED_CHECK(P.rows() == index.size() && P.cols() == index.dims(), "index does not match P");
  const double size = RmsRadius(P);
  ReflectionFit fit;
  fit.normal = normal.normalized();
  fit.offset = offset;
  Score(P, index, size, options, &fit);
  // Iterate until the plane stops moving; the trimmed score may rise on the way out of a poor
  // start, so the best iterate seen is returned.
  ReflectionFit best = fit;
  for (int it = 0; it < options.max_iterations; ++it) {
    const double threshold = TrimThreshold(fit.residual, options.trim_fraction);
    Eigen::VectorXd w = (fit.residual.array() <= threshold).cast<double>();
    Eigen::VectorXd n = fit.normal;
    double c = fit.offset;
    if (!FitReflection(P, fit.sigma, w, &n, &c)) break;
    const double turn = std::acos(std::clamp(std::abs(n.dot(fit.normal)), 0.0, 1.0));
    const bool still = turn < options.tolerance &&
                       std::abs(c - fit.offset) < options.tolerance * std::max(size, 1e-300);
    fit.normal = n;
    fit.offset = c;
    fit.iterations = it + 1;
    Score(P, index, size, options, &fit);
    if (fit.score <= best.score) best = fit;
    if (still) {
      best.converged = true;
      break;
    }
  }
  best.iterations = fit.iterations;
  return best;
}

IntrinsicCheck::IntrinsicCheck(const Eigen::MatrixXd& Dss, int num_pairs, unsigned seed)
    : Dss_(Dss) {
  if (Dss.rows() != Dss.cols()) {
    throw InvalidInputError("intrinsic check: distances of " + std::to_string(Dss.rows()) + " x " +
                            std::to_string(Dss.cols()) + " points");
  }
  const int n = static_cast<int>(Dss.rows());
  if (n < 2) return;
  auto add = [&](int i, int j) {
    first_.push_back(i);
    second_.push_back(j);
    distance_.push_back(Dss(i, j));
    distance_sum_ += Dss(i, j);
  };
  const long long all_pairs = static_cast<long long>(n) * (n - 1) / 2;
  if (all_pairs <= num_pairs) {
    for (int i = 0; i < n; ++i) {
      for (int j = i + 1; j < n; ++j) add(i, j);
    }
  } else {
    std::mt19937 rng(seed);
    std::uniform_int_distribution<int> pick(0, n - 1);
    while (static_cast<int>(distance_.size()) < num_pairs) {
      const int i = pick(rng), j = pick(rng);
      if (i != j) add(i, j);
    }
  }
}

double IntrinsicCheck::Distortion(const std::vector<int>& sigma, double trim_fraction) const {
  if (static_cast<Eigen::Index>(sigma.size()) != Dss_.rows()) {
    throw InvalidInputError("intrinsic check: a self map of " + std::to_string(sigma.size()) +
                            " points for " + std::to_string(Dss_.rows()));
  }
  if (distance_.empty() || distance_sum_ <= 0.0) return 0.0;
  std::vector<double> diff(distance_.size());
  for (size_t k = 0; k < diff.size(); ++k) {
    diff[k] = std::abs(distance_[k] - Dss_(sigma[first_[k]], sigma[second_[k]]));
  }
  std::sort(diff.begin(), diff.end());
  const size_t keep = std::max<size_t>(1, static_cast<size_t>(std::ceil(trim_fraction * diff.size())));
  double sum = 0.0;
  for (size_t k = 0; k < keep; ++k) sum += diff[k];
  return (sum / keep) / (distance_sum_ / diff.size());
}

Eigen::VectorXd SymmetryConfidence(const Eigen::VectorXd& residual, const std::vector<int>& sigma,
                                   double size) {
  const int n = static_cast<int>(residual.size());
  Eigen::VectorXd c(n);
  if (n == 0) return c;
  std::vector<double> sorted(residual.data(), residual.data() + n);
  std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.end());
  const double h = std::max(2.0 * sorted[n / 2], 1e-3 * size);
  for (int i = 0; i < n; ++i) {
    const double r = residual(i) / std::max(h, 1e-300);
    c(i) = std::exp(-r * r);
    if (sigma[sigma[i]] != i) c(i) *= 0.5;
  }
  return c;
}

SymmetryResult MakeSymmetryResult(const Eigen::MatrixXd& Y3s, const KnnIndex& index,
                                  const Eigen::VectorXd& normal, double offset,
                                  const ReflectionSearchOptions& options, int iterations_3d,
                                  const std::string& message) {
  ReflectionFit fit;
  if (iterations_3d > 0) {
    ReflectionSearchOptions o = options;
    o.max_iterations = iterations_3d;
    fit = RefineReflection(Y3s, index, normal, offset, o);
  } else {
    fit = EvaluateReflection(Y3s, index, normal, offset, options);
  }
  SymmetryResult result;
  result.normal = fit.normal;
  result.offset = fit.offset;
  result.sigma = fit.sigma;
  result.confidence = SymmetryConfidence(fit.residual, fit.sigma, RmsRadius(Y3s));
  result.score = fit.score;
  result.status.converged = fit.converged || iterations_3d == 0;
  result.status.iterations = fit.iterations;
  result.status.residual = fit.score;
  result.status.message = message;
  return result;
}

Eigen::MatrixXd SampleDistances(const Eigen::MatrixXd& D, const std::vector<int>& samples) {
  const int n = static_cast<int>(samples.size());
  if (D.rows() != n) {
    throw InvalidInputError("symmetry: D has " + std::to_string(D.rows()) + " rows for " +
                            std::to_string(n) + " samples");
  }
  Eigen::MatrixXd Dss(n, n);
  for (int j = 0; j < n; ++j) {
    if (samples[j] < 0 || samples[j] >= D.cols()) {
      throw InvalidInputError("symmetry: sample id out of range");
    }
    Dss.col(j) = D.col(samples[j]);
  }
  Dss = 0.5 * (Dss + Dss.transpose()).eval();
  Dss.diagonal().setZero();
  return Dss;
}

}  // namespace symembed

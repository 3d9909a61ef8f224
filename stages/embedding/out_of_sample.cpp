#include "stages/embedding/out_of_sample.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.h"
#include "core/parallel.h"

namespace symembed {

bool OutOfSampleOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  why << FirstViolation({{"neighbors", kNeighbors, neighbors},
                         {"weight_power", kWeightPower, weight_power},
                         {"max_iterations", kMaxIterations, max_iterations},
                         {"tolerance", kTolerance, tolerance},
                         {"threads", kThreads, threads}});
  if (why.str().empty()) return true;
  if (error) *error = why.str();
  return false;
}

namespace {

// Fixed upper bounds keep the per-query work free of heap allocation.
constexpr int kMaxDims = 8;
constexpr int kMaxNeighbors = 64;
using Vec = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxDims, 1>;
using Sym = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxDims, kMaxDims>;
using Mat =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, kMaxNeighbors, kMaxDims>;

// One query's neighbourhood: sample positions P (k x dims), distances d and weights w.
struct Local {
  Mat P;
  std::vector<double> d, w;
};

// Weighted stress sum_j w_j (||y - p_j|| - d_j)^2 of y and, when A and g are given, the
// Gauss-Newton normal equations of its residuals. A sample at distance 0 contributes
// w_j ||y - p_j||^2, which is smooth, so its exact (identity) Hessian term is used.
double LocalStress3(const Local& local, const Vec& y, Sym* A, Vec* g);

double LocalStress(const Local& local, const Vec& y, Sym* A, Vec* g) {
  const int dims = static_cast<int>(y.size());
  if (dims == 3) return LocalStress3(local, y, A, g);
  double stress = 0.0;
  if (A != nullptr) {
    A->setZero(dims, dims);
    g->setZero(dims);
  }
  for (int j = 0; j < local.P.rows(); ++j) {
    const Vec diff = y - local.P.row(j).transpose();
    const double len = diff.norm();
    const double r = len - local.d[j];
    const double w = local.w[j];
    stress += w * r * r;
    if (A == nullptr) continue;
    if (local.d[j] == 0.0) {
      A->diagonal().array() += w;
      *g += w * diff;
    } else if (len > 0.0) {
      const Vec u = diff / len;
      A->noalias() += w * u * u.transpose();
      *g += (w * r) * u;
    }
  }
  return stress;
}

// LocalStress in three dimensions on scalars: the Eigen expressions' operations one by one, in
// their order (a squared norm sums (x^2 + y^2) + z^2; the outer product adds u_c (w u_r) to
// A(r, c)), so the values are the same, without the loops over a run-time size.
double LocalStress3(const Local& local, const Vec& y, Sym* A, Vec* g) {
  const double y0 = y(0), y1 = y(1), y2 = y(2);
  double a[3][3] = {}, gs[3] = {};
  double stress = 0.0;
  for (int j = 0; j < local.P.rows(); ++j) {
    const double diff[3] = {y0 - local.P(j, 0), y1 - local.P(j, 1), y2 - local.P(j, 2)};
    const double len = std::sqrt(diff[0] * diff[0] + diff[1] * diff[1] + diff[2] * diff[2]);
    const double r = len - local.d[j];
    const double w = local.w[j];
    stress += w * r * r;
    if (A == nullptr) continue;
    if (local.d[j] == 0.0) {
      for (int c = 0; c < 3; ++c) {
        a[c][c] += w;
        gs[c] += w * diff[c];
      }
    } else if (len > 0.0) {
      const double u[3] = {diff[0] / len, diff[1] / len, diff[2] / len};
      const double wu[3] = {w * u[0], w * u[1], w * u[2]};
      for (int c = 0; c < 3; ++c) {
        for (int row = 0; row < 3; ++row) a[row][c] += u[c] * wu[row];
      }
      const double wr = w * r;
      for (int c = 0; c < 3; ++c) gs[c] += wr * u[c];
    }
  }
  if (A != nullptr) {
    A->resize(3, 3);
    g->resize(3);
    for (int row = 0; row < 3; ++row) {
      for (int c = 0; c < 3; ++c) (*A)(row, c) = a[row][c];
      (*g)(row) = gs[row];
    }
  }
  return stress;
}

// Levenberg-Marquardt on the local stress: Gauss-Newton steps, damped whenever a step would
// increase stress, so the stress never increases.
Vec Minimise(const Local& local, Vec y, int max_iterations, double step_tolerance) {
  const int dims = static_cast<int>(y.size());
  Sym A(dims, dims);
  Vec g(dims);
  double stress = LocalStress(local, y, &A, &g);
  double damping = 1e-6;
  for (int it = 0; it < max_iterations; ++it) {
    const double scale = std::max(A.trace() / dims, std::numeric_limits<double>::min());
    bool accepted = false;
    Vec step(dims);
    while (damping < 1e8) {
      Sym M = A;
      M.diagonal().array() += damping * scale;
      step = -M.ldlt().solve(g);
      const Vec trial = y + step;
      const double trial_stress = LocalStress(local, trial, nullptr, nullptr);
      if (trial_stress <= stress) {
        y = trial;
        stress = trial_stress;
        accepted = true;
        damping = std::max(1e-9, damping * 0.1);
        break;
      }
      damping *= 10.0;
    }
    if (!accepted || step.norm() <= step_tolerance) break;
    stress = LocalStress(local, y, &A, &g);
  }
  return y;
}

// Indices of the k smallest entries of d (ascending), by insertion into a sorted list of k:
// one comparison for most entries, since k is much smaller than d's length.
void NearestK(const double* d, int n, int k, std::vector<int>& idx, std::vector<double>& val) {
  idx.clear();
  val.clear();
  for (int j = 0; j < n; ++j) {
    const double x = d[j];
    if (static_cast<int>(val.size()) == k && !(x < val.back())) continue;
    int pos = static_cast<int>(val.size());
    if (pos == k) {
      --pos;  // drop the current largest
    } else {
      val.push_back(0.0);
      idx.push_back(0);
    }
    while (pos > 0 && val[pos - 1] > x) {
      val[pos] = val[pos - 1];
      idx[pos] = idx[pos - 1];
      --pos;
    }
    val[pos] = x;
    idx[pos] = j;
  }
}

}  // namespace

Eigen::MatrixXd PlaceOutOfSample(const Eigen::MatrixXd& Ys, const Eigen::MatrixXd& D,
                                 const std::vector<int>& columns,
                                 const OutOfSampleOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw ConfigError("OutOfSampleOptions: " + why);
  const int n = static_cast<int>(Ys.rows());
  const int dims = static_cast<int>(Ys.cols());
  if (D.rows() != n || n < 1 || dims < 1 || dims > kMaxDims) {
    std::ostringstream m;
    m << "PlaceOutOfSample: " << n << " samples in " << dims << "D (at most " << kMaxDims
      << "), distances have " << D.rows() << " rows";
    throw InvalidInputError(m.str());
  }
  for (int c : columns) {
    if (c < 0 || c >= D.cols()) {
      throw InvalidInputError("PlaceOutOfSample: column " + std::to_string(c) + " out of range");
    }
  }
  const int m = columns.empty() ? static_cast<int>(D.cols()) : static_cast<int>(columns.size());
  const int k = std::min(options.neighbors, n);
  const bool weighted = options.weight_power > 0.0;
  Eigen::MatrixXd Y(m, dims);
  constexpr int kGrain = 64;
  const int blocks = (m + kGrain - 1) / kGrain;
  ParallelFor(
      blocks,
      [&](int b) {
        std::vector<int> idx;
        idx.reserve(k);
        Local local;
        local.P.resize(k, dims);
        local.d.reserve(k);
        local.w.assign(k, 1.0);
        const int end = std::min(m, (b + 1) * kGrain);
        for (int q = b * kGrain; q < end; ++q) {
          const int col = columns.empty() ? q : columns[q];
          NearestK(D.col(col).data(), n, k, idx, local.d);
          if (!std::isfinite(local.d.back()) || local.d.front() < 0.0) {
            throw InvalidInputError("PlaceOutOfSample: distances of column " + std::to_string(col) +
                                    " are negative or not finite");
          }
          if (weighted && local.d.front() == 0.0) {
            // The limit of the weighted problem: infinite weight on a coincident sample.
            Y.row(q) = Ys.row(idx.front());
            continue;
          }
          for (int j = 0; j < k; ++j) local.P.row(j) = Ys.row(idx[j]);
          double mean_d = 0.0;
          for (double v : local.d) mean_d += v;
          mean_d /= k;
          if (weighted) {
            // Relative to the nearest distance, so the weights are scale-free and bounded.
            for (int j = 0; j < k; ++j) {
              local.w[j] = std::pow(local.d.front() / local.d[j], options.weight_power);
            }
          }
          // Start: 1/d^2-weighted barycentre of the neighbours.
          const double eps = 1e-12 * std::max(mean_d, std::numeric_limits<double>::min());
          double wsum = 0.0;
          Vec y = Vec::Zero(dims);
          for (int j = 0; j < k; ++j) {
            const double w = 1.0 / ((local.d[j] + eps) * (local.d[j] + eps));
            y += w * local.P.row(j).transpose();
            wsum += w;
          }
          y /= wsum;
          y = Minimise(local, y, options.max_iterations, options.tolerance * mean_d);
          Y.row(q) = y.transpose();
        }
      },
      options.threads);
  return Y;
}

}  // namespace symembed

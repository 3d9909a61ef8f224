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
  if (neighbors < 1 || neighbors > 64) why << "neighbors must be in [1, 64], got " << neighbors;
  else if (max_iterations < 0) why << "max_iterations must be >= 0, got " << max_iterations;
  else if (!(tolerance >= 0.0)) why << "tolerance must be >= 0, got " << tolerance;
  else if (threads < 0) why << "threads must be >= 0, got " << threads;
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
using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor, kMaxNeighbors,
                          kMaxDims>;

// Stress of y against the samples P (k x dims) at distances d, and, when A and g are given, the
// Gauss-Newton normal equations of the residuals ||y - p_j|| - d_j. A sample at distance 0
// contributes ||y - p_j||^2, which is smooth, so its exact (identity) Hessian term is used.
double LocalStress(const Mat& P, const std::vector<double>& d, const Vec& y, Sym* A, Vec* g) {
  const int dims = static_cast<int>(y.size());
  double stress = 0.0;
  if (A != nullptr) {
    A->setZero(dims, dims);
    g->setZero(dims);
  }
  for (int j = 0; j < P.rows(); ++j) {
    const Vec diff = y - P.row(j).transpose();
    const double len = diff.norm();
    const double r = len - d[j];
    stress += r * r;
    if (A == nullptr) continue;
    if (d[j] == 0.0) {
      A->diagonal().array() += 1.0;
      *g += diff;
    } else if (len > 0.0) {
      const Vec u = diff / len;
      A->noalias() += u * u.transpose();
      *g += r * u;
    }
  }
  return stress;
}

// Levenberg-Marquardt on the local stress: Gauss-Newton steps, damped whenever a step would
// increase stress, so the stress never increases. Converges quadratically for exact distances
// even when the samples are nearly coplanar (the normal direction of a surface), where
// first-order updates crawl.
Vec Minimise(const Mat& P, const std::vector<double>& d, Vec y, int max_iterations,
             double step_tolerance) {
  const int dims = static_cast<int>(y.size());
  Sym A(dims, dims);
  Vec g(dims);
  double stress = LocalStress(P, d, y, &A, &g);
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
      const double trial_stress = LocalStress(P, d, trial, nullptr, nullptr);
      if (trial_stress <= stress) {
        y = trial;
        accepted = true;
        damping = std::max(1e-9, damping * 0.1);
        break;
      }
      damping *= 10.0;
    }
    if (!accepted || step.norm() <= step_tolerance) break;
    stress = LocalStress(P, d, y, &A, &g);
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
    if (pos == k) --pos;  // drop the current largest
    else {
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
  if (D.rows() != n || n < 1 || dims < 1) {
    std::ostringstream m;
    m << "PlaceOutOfSample: " << n << " samples in " << dims << "D, distances have " << D.rows()
      << " rows";
    throw InvalidInputError(m.str());
  }
  for (int c : columns) {
    if (c < 0 || c >= D.cols()) {
      throw InvalidInputError("PlaceOutOfSample: column " + std::to_string(c) + " out of range");
    }
  }
  const int m = columns.empty() ? static_cast<int>(D.cols()) : static_cast<int>(columns.size());
  const int k = std::min(options.neighbors, n);
  if (dims > kMaxDims) {
    throw InvalidInputError("PlaceOutOfSample: at most " + std::to_string(kMaxDims) +
                            " dimensions supported, got " + std::to_string(dims));
  }
  Eigen::MatrixXd Y(m, dims);
  constexpr int kGrain = 64;
  const int blocks = (m + kGrain - 1) / kGrain;
  ParallelFor(
      blocks,
      [&](int b) {
        std::vector<int> idx;
        std::vector<double> val;
        idx.reserve(k);
        val.reserve(k);
        Mat P(k, dims);
        const int end = std::min(m, (b + 1) * kGrain);
        for (int q = b * kGrain; q < end; ++q) {
          const int col = columns.empty() ? q : columns[q];
          NearestK(D.col(col).data(), n, k, idx, val);
          if (!std::isfinite(val.back()) || val.front() < 0.0) {
            throw InvalidInputError("PlaceOutOfSample: distances of column " +
                                    std::to_string(col) + " are negative or not finite");
          }
          for (int j = 0; j < k; ++j) P.row(j) = Ys.row(idx[j]);
          double mean_d = 0.0;
          for (double v : val) mean_d += v;
          mean_d /= k;
          // Start: 1/d^2-weighted barycentre (a query on top of a sample starts on it).
          const double eps = 1e-12 * std::max(mean_d, std::numeric_limits<double>::min());
          double wsum = 0.0;
          Vec y = Vec::Zero(dims);
          for (int j = 0; j < k; ++j) {
            const double w = 1.0 / ((val[j] + eps) * (val[j] + eps));
            y += w * P.row(j).transpose();
            wsum += w;
          }
          y /= wsum;
          y = Minimise(P, val, y, options.max_iterations, options.tolerance * mean_d);
          Y.row(q) = y.transpose();
        }
      },
      options.threads);
  return Y;
}

}  // namespace symembed

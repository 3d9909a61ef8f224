#include "stages/symmetry/plane3d.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/errors.h"
#include "core/parallel.h"

namespace symembed {

namespace {

Eigen::MatrixXd SampleRows(const Eigen::MatrixXd& Y, const std::vector<int>& samples) {
  Eigen::MatrixXd P(samples.size(), Y.cols());
  for (size_t i = 0; i < samples.size(); ++i) {
    if (samples[i] < 0 || samples[i] >= Y.rows()) {
      throw InvalidInputError("symmetry: sample id out of range");
    }
    P.row(i) = Y.row(samples[i]);
  }
  return P;
}

// Principal axes, then n points of a Fibonacci lattice on the upper hemisphere.
std::vector<Eigen::VectorXd> StartingNormals(const Eigen::MatrixXd& P, int n) {
  std::vector<Eigen::VectorXd> normals;
  const Eigen::MatrixXd C = P.rowwise() - P.colwise().mean();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(C.transpose() * C);
  for (int a = 2; a >= 0; --a) normals.push_back(eig.eigenvectors().col(a));
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < n; ++k) {
    const double z = (k + 0.5) / n;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    normals.push_back(Eigen::Vector3d(r * std::cos(golden * k), r * std::sin(golden * k), z));
  }
  return normals;
}

}  // namespace

ReflectionFit SearchPlanes3d(const Eigen::MatrixXd& P, const KnnIndex& index,
                             const IntrinsicCheck& intrinsic_check, const Plane3dOptions& options,
                             double* total, double* intrinsic, int* iterations) {
  const Eigen::VectorXd centroid = P.colwise().mean().transpose();
  *total = std::numeric_limits<double>::infinity();
  *intrinsic = 0.0;
  // Each start refined on its own (in parallel), then taken in order: the first of equal totals
  // wins, whatever the threads.
  const std::vector<Eigen::VectorXd> starts = StartingNormals(P, options.num_directions);
  std::vector<ReflectionFit> fits(starts.size());
  std::vector<double> distortions(starts.size(), 0.0);
  ParallelFor(
      static_cast<int>(starts.size()),
      [&](int k) {
        const Eigen::VectorXd& n = starts[k];
        fits[k] = RefineReflection(P, index, n, n.dot(centroid), options.search);
        if (std::isfinite(fits[k].score) && options.intrinsic.weight > 0.0) {
          distortions[k] = intrinsic_check.Distortion(fits[k].sigma, options.search.trim_fraction);
        }
      },
      options.threads);
  ReflectionFit best;
  for (size_t k = 0; k < starts.size(); ++k) {
    *iterations += fits[k].iterations;
    if (!std::isfinite(fits[k].score)) continue;
    const double t = fits[k].score + options.intrinsic.weight * distortions[k];
    if (t < *total) {
      *total = t;
      *intrinsic = distortions[k];
      best = std::move(fits[k]);
    }
  }
  return best;
}

SymmetryResult DetectSymmetryPlane3d(const Eigen::MatrixXd& D, const std::vector<int>& samples,
                                     const Eigen::MatrixXd& Y, const Plane3dOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("symmetry plane3d: " + error);
  if (Y.cols() != 3) throw InvalidInputError("symmetry plane3d: the embedding must be 3D");
  if (samples.size() < 4) throw InvalidInputError("symmetry plane3d: fewer than 4 samples");
  const Eigen::MatrixXd P = SampleRows(Y, samples);
  const Eigen::MatrixXd Dss = SampleDistances(D, samples);
  const KnnIndex index(P);
  double total = 0.0, intrinsic = 0.0;
  int iterations = 0;
  const IntrinsicCheck intrinsic_check(Dss, options.intrinsic.pairs,
                                       static_cast<unsigned>(options.intrinsic.seed));
  const ReflectionFit best =
      SearchPlanes3d(P, index, intrinsic_check, options, &total, &intrinsic, &iterations);
  if (!std::isfinite(total)) {
    throw InvalidInputError("symmetry plane3d: every candidate plane was rejected (flat or "
                            "degenerate sample set)");
  }
  std::ostringstream message;
  message << "plane3d: score " << best.score << ", intrinsic distortion " << intrinsic;
  SymmetryResult result =
      MakeSymmetryResult(P, index, best.normal, best.offset, options.search, 0, message.str());
  result.status.iterations = iterations;
  result.status.converged = best.converged;
  return result;
}

}  // namespace symembed

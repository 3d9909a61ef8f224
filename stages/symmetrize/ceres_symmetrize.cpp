#include "stages/symmetrize/ceres_symmetrize.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "core/errors.h"
#include "core/knn.h"
#include "core/procrustes.h"
#include "stages/symmetrize/symmetrize_common.h"
#include "stages/symmetrize/symmetrize_costs.h"

namespace symembed {

std::vector<std::pair<int, int>> KnnGraphEdges(const Eigen::MatrixX3d& P, int k) {
  const int n = static_cast<int>(P.rows());
  std::set<std::pair<int, int>> edges;
  if (n < 2) return {};
  const int kk = std::min(k + 1, n);
  const KnnIndex index(P);
  Eigen::MatrixXi nn;
  index.Query(P, kk, &nn, nullptr, 1);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < kk; ++j) {
      const int o = nn(i, j);
      if (o != i) edges.insert({std::min(i, o), std::max(i, o)});
    }
  }
  return {edges.begin(), edges.end()};
}

std::vector<std::vector<std::pair<int, double>>> MirrorWeights(const Eigen::MatrixX3d& P,
                                                               const std::vector<int>& sigma,
                                                               int k) {
  const int n = static_cast<int>(P.rows());
  std::vector<std::vector<std::pair<int, double>>> out(n);
  k = std::min(k, n);
  if (k <= 1) {
    for (int i = 0; i < n; ++i) out[i] = {{sigma[i], 1.0}};
    return out;
  }
  Eigen::MatrixX3d Q = P;
  Q.col(0) *= -1.0;
  Eigen::MatrixXi nn;
  Eigen::MatrixXd dist;
  KnnIndex(P).Query(Q, k, &nn, &dist, 1);
  for (int i = 0; i < n; ++i) {
    // Mirror point on a sample (up to rounding): that sample alone. Where the embedding is not
    // symmetric, the mirror point is not near sigma(i) (which comes from the symmetry stage,
    // possibly from intrinsic information); sigma(i) alone is kept there too.
    bool near_sigma = false;
    for (int j = 0; j < k; ++j) near_sigma |= nn(i, j) == sigma[i];
    if (!near_sigma) {
      out[i] = {{sigma[i], 1.0}};
      continue;
    }
    if (dist(i, 0) <= 1e-12 * std::max(1.0, dist(i, k - 1))) {
      out[i] = {{nn(i, 0), 1.0}};
      continue;
    }
    // Locally linear reconstruction: minimise ||sum_j w_j p_j - q||^2 with sum_j w_j = 1,
    // regularised because k neighbours in 3D give a singular local Gram matrix.
    Eigen::MatrixXd N(k, 3);
    for (int j = 0; j < k; ++j) N.row(j) = P.row(nn(i, j)) - Q.row(i);
    Eigen::MatrixXd G = N * N.transpose();
    G.diagonal().array() += 1e-3 * G.trace() + 1e-300;
    Eigen::VectorXd w = G.ldlt().solve(Eigen::VectorXd::Ones(k));
    w /= w.sum();
    for (int j = 0; j < k; ++j) out[i].push_back({nn(i, j), w(j)});
  }
  return out;
}

double MirrorResidual(const Eigen::MatrixX3d& X,
                      const std::vector<std::vector<std::pair<int, double>>>& weights) {
  if (X.rows() == 0) return 0.0;
  const double size = RmsRadius(X);
  double sum = 0.0;
  for (int i = 0; i < X.rows(); ++i) {
    Eigen::RowVector3d m = Eigen::RowVector3d::Zero();
    for (const auto& [j, w] : weights[i]) m += w * X.row(j);
    Eigen::RowVector3d r = X.row(i);
    r.x() = -r.x();
    sum += (r - m).norm();
  }
  return size > 0.0 ? sum / X.rows() / size : 0.0;
}

double GraphStress(const Eigen::MatrixX3d& P, const Eigen::MatrixX3d& X, int k) {
  double num = 0.0, den = 0.0;
  for (const auto& [i, j] : KnnGraphEdges(P, k)) {
    const double d0 = (P.row(i) - P.row(j)).norm();
    const double d = (X.row(i) - X.row(j)).norm();
    num += (d - d0) * (d - d0);
    den += d0 * d0;
  }
  return den > 0.0 ? std::sqrt(num / den) : 0.0;
}

SymmetrizeEnergy CeresSymmetrizeEnergy(const Eigen::MatrixX3d& P, const SymmetryResult& symmetry,
                                       const CeresSymmetrizeOptions& options) {
  const int n = static_cast<int>(P.rows());
  const std::vector<int>& sigma = symmetry.sigma;
  SymmetrizeEnergy energy;
  energy.edges = KnnGraphEdges(P, options.graph_neighbors);
  for (const auto& [i, j] : energy.edges) energy.lengths.push_back((P.row(i) - P.row(j)).norm());
  energy.mirror = MirrorWeights(P, sigma, options.mirror_neighbors);
  energy.symmetry_weight = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < n; ++i) {
    const double c = symmetry.confidence.size() == n ? symmetry.confidence(i) : 1.0;
    if (options.symmetry_weight > 0.0 && c > 0.0) {
      energy.symmetry_weight(i) = options.symmetry_weight * c;
    }
    if (options.mirror_neighbors == 1 && sigma[i] == i && options.plane_weight > 0.0) {
      energy.on_plane.push_back(i);
    }
  }
  energy.plane_weight = options.plane_weight;
  energy.anchor_weight = options.anchor_weight;
  energy.anchor = P;
  return energy;
}

namespace {

// The Ceres problem of `energy` over the unknowns x (one 3-vector per sample, contiguous),
// residuals scaled by inv_s: graph stress per edge, then per sample its on-plane, symmetry and
// anchor terms.
void BuildSymmetrizeProblem(const SymmetrizeEnergy& energy, const Eigen::MatrixX3d& P,
                            const CeresSymmetrizeOptions& options, double inv_s,
                            std::vector<double>* x, ceres::Problem* problem) {
  const int n = static_cast<int>(P.rows());
  auto block = [&](int i) { return x->data() + 3 * static_cast<size_t>(i); };
  for (int i = 0; i < n; ++i) problem->AddParameterBlock(block(i), 3);
  for (size_t e = 0; e < energy.edges.size(); ++e) {
    const auto [i, j] = energy.edges[e];
    problem->AddResidualBlock(new EdgeStressCost(energy.lengths[e], inv_s), nullptr, block(i),
                              block(j));
  }
  const Eigen::Matrix3d M = MirrorX(), I = Eigen::Matrix3d::Identity();
  std::vector<bool> on_plane(n, false);
  for (int i : energy.on_plane) on_plane[i] = true;
  for (int i = 0; i < n; ++i) {
    if (on_plane[i]) {
      problem->AddResidualBlock(new OnPlaneCost(std::sqrt(options.plane_weight) * inv_s), nullptr,
                                block(i));
    }
    if (energy.symmetry_weight(i) > 0.0) {
      // M x_i - sum_j w_ij x_j, with x_i's own coefficient merged (blocks must be distinct).
      std::vector<Eigen::Matrix3d> A = {M};
      std::vector<double*> blocks = {block(i)};
      for (const auto& [j, w] : energy.mirror[i]) {
        if (j == i) {
          A[0] -= w * I;
        } else {
          A.push_back(-w * I);
          blocks.push_back(block(j));
        }
      }
      problem->AddResidualBlock(
          new LinearResidualCost(std::move(A), std::sqrt(energy.symmetry_weight(i)) * inv_s),
          nullptr, blocks);
    }
    if (options.anchor_weight > 0.0) {
      const double p[3] = {P(i, 0), P(i, 1), P(i, 2)};
      problem->AddResidualBlock(new AnchorCost(p, std::sqrt(options.anchor_weight) * inv_s),
                                nullptr, block(i));
    }
  }
}

// Sparse normal Cholesky with the first sparse library Ceres was built with, else CGNR.
ceres::Solver::Options SymmetrizeSolverOptions(const CeresSymmetrizeOptions& options) {
  ceres::Solver::Options solver;
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = options.function_tolerance;
  solver.num_threads = options.threads;
  solver.logging_type = ceres::SILENT;
  solver.minimizer_progress_to_stdout = false;
  if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::EIGEN_SPARSE)) {
    solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    solver.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  } else if (ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)) {
    solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
    solver.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
  } else {
    solver.linear_solver_type = ceres::CGNR;
  }
  return solver;
}

// The status message: asymmetry, mirror residual and graph stress of the samples P before and X
// after, the warm start, and Ceres' report.
std::string SymmetrizeMessage(const SymmetrizeResult& result, const Eigen::MatrixX3d& P,
                              const Eigen::MatrixX3d& X, const SymmetrizeEnergy& energy,
                              const CeresSymmetrizeOptions& options,
                              const MajorizationResult& warm,
                              const ceres::Solver::Summary& summary) {
  std::ostringstream message;
  message << "asymmetry " << result.asymmetry_before << " -> " << result.asymmetry_after
          << ", mirror residual " << MirrorResidual(P, energy.mirror) << " -> "
          << MirrorResidual(X, energy.mirror) << ", graph stress "
          << GraphStress(P, X, options.graph_neighbors) << "; ";
  if (options.warm_start_iterations > 0) {
    message << "warm start: " << warm.iterations << " majorization iterations, energy "
            << warm.energy_before << " -> " << warm.energy_after << "; ";
  }
  if (options.max_iterations > 0) {
    message << summary.BriefReport();
  } else {
    message << "no Levenberg-Marquardt iterations (max_iterations 0)";
  }
  return message.str();
}

}  // namespace

SymmetrizeResult SymmetrizeCeres(const Eigen::MatrixXd& Y_in, const std::vector<int>& samples,
                                 const SymmetryResult& symmetry,
                                 const CeresSymmetrizeOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("symmetrize ceres: " + error);
  const Eigen::MatrixX3d Y = MovePlaneToX0(Y_in, symmetry.normal, symmetry.offset);
  const Eigen::MatrixX3d P = SampleRows3(Y, samples);
  const int n = static_cast<int>(samples.size());
  const double size = RmsRadius(P);
  if (!(size > 0.0)) throw InvalidInputError("symmetrize ceres: all samples coincide");

  // The energy's terms, shared by the warm start and the Ceres problem.
  const SymmetrizeEnergy energy = CeresSymmetrizeEnergy(P, symmetry, options);
  MajorizationResult warm;
  warm.X = P;
  if (options.warm_start_iterations > 0) {
    warm = MajorizeSymmetrizeEnergy(energy, P, options.warm_start_iterations,
                                    options.warm_start_tolerance);
  }
  Eigen::MatrixX3d X = warm.X;
  ceres::Solver::Summary summary;
  if (options.max_iterations > 0) {
    std::vector<double> x(3 * static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) x[3 * i + c] = warm.X(i, c);
    }
    ceres::Problem problem;
    BuildSymmetrizeProblem(energy, P, options, 1.0 / size, &x, &problem);
    ceres::Solve(SymmetrizeSolverOptions(options), &problem, &summary);
    if (!summary.IsSolutionUsable()) {
      throw SolverError("symmetrize ceres: " + summary.message);
    }
    for (int i = 0; i < n; ++i) {
      for (int c = 0; c < 3; ++c) X(i, c) = x[3 * i + c];
    }
  }
  SymmetrizeResult result;
  result.asymmetry_before = Asymmetry(P, symmetry.sigma);
  result.Y = FollowSamples(Y, samples, X, options.follow_neighbors);
  result.asymmetry_after = Asymmetry(X, symmetry.sigma);
  if (options.max_iterations > 0) {
    result.status.converged = summary.termination_type == ceres::CONVERGENCE;
    result.status.iterations = static_cast<int>(summary.iterations.size());
    result.status.residual = summary.final_cost;
  } else {
    // Ceres' cost of the same positions: half the sum of squared residuals, each divided by size.
    result.status.converged = warm.iterations < options.warm_start_iterations;
    result.status.iterations = warm.iterations;
    result.status.residual = 0.5 * energy.Evaluate(X) / (size * size);
  }
  result.status.message = SymmetrizeMessage(result, P, X, energy, options, warm, summary);
  return result;
}

}  // namespace symembed

#include "stages/symmetrize/stress_majorization.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cmath>
#include <optional>

#include "core/errors.h"
#include "core/ldlt_columns.h"

namespace symembed {

namespace {

// M = diag(-1, 1, 1): the sign of coordinate c under the reflection.
double MirrorSign(int c) { return c == 0 ? -1.0 : 1.0; }

// The symmetry residual of sample i along one coordinate as sparse coefficients:
// sign * x_i - sum_j w_ij x_j, with x_i's own weight merged.
std::vector<std::pair<int, double>> SymmetryRow(int i, double sign,
                                                const std::vector<std::pair<int, double>>& w) {
  std::vector<std::pair<int, double>> row = {{i, sign}};
  for (const auto& [j, wj] : w) {
    if (j == i) {
      row[0].second -= wj;
    } else {
      row.push_back({j, -wj});
    }
  }
  return row;
}

}  // namespace

double SymmetrizeEnergy::Evaluate(const Eigen::MatrixX3d& X) const {
  double e = 0.0;
  for (size_t k = 0; k < edges.size(); ++k) {
    const double r = (X.row(edges[k].first) - X.row(edges[k].second)).norm() - lengths[k];
    e += r * r;
  }
  for (int i = 0; i < static_cast<int>(mirror.size()); ++i) {
    if (symmetry_weight(i) <= 0.0) continue;
    Eigen::RowVector3d r = X.row(i);
    r.x() = -r.x();
    for (const auto& [j, w] : mirror[i]) r -= w * X.row(j);
    e += symmetry_weight(i) * r.squaredNorm();
  }
  for (int i : on_plane) e += plane_weight * X(i, 0) * X(i, 0);
  if (anchor_weight > 0.0) e += anchor_weight * (X - anchor).squaredNorm();
  return e;
}

MajorizationResult MajorizeSymmetrizeEnergy(const SymmetrizeEnergy& energy,
                                            const Eigen::MatrixX3d& X0, int max_iterations,
                                            double relative_tolerance) {
  const int n = static_cast<int>(X0.rows());
  SYMEMBED_CHECK(static_cast<int>(energy.mirror.size()) == n &&
                     energy.symmetry_weight.size() == n &&
                     energy.lengths.size() == energy.edges.size(),
                 "stress majorization: inconsistent energy terms");
  // The matrices of the bound: coordinate 0 (reflected) and coordinates 1, 2 (equal).
  Eigen::SparseMatrix<double> A[2];
  for (int m = 0; m < 2; ++m) {
    const int c = m == 0 ? 0 : 1;
    std::vector<Eigen::Triplet<double>> t;
    for (const auto& [i, j] : energy.edges) {
      t.emplace_back(i, i, 1.0);
      t.emplace_back(j, j, 1.0);
      t.emplace_back(i, j, -1.0);
      t.emplace_back(j, i, -1.0);
    }
    for (int i = 0; i < n; ++i) {
      const double s = energy.symmetry_weight(i);
      if (s <= 0.0) continue;
      const auto row = SymmetryRow(i, MirrorSign(c), energy.mirror[i]);
      for (const auto& [a, ca] : row) {
        for (const auto& [b, cb] : row) t.emplace_back(a, b, s * ca * cb);
      }
    }
    if (c == 0) {
      for (int i : energy.on_plane) t.emplace_back(i, i, energy.plane_weight);
    }
    A[m].resize(n, n);
    A[m].setFromTriplets(t.begin(), t.end());
  }
  // A proximal term eps ||x - z||^2 makes the systems definite (without anchors the energy does
  // not change under translations along the plane); it vanishes at a fixed point.
  const double eps = 1e-6 * std::max(A[1].diagonal().mean(), 1e-300);
  SparseLdlt solver[2];
  for (int m = 0; m < 2; ++m) {
    for (int i = 0; i < n; ++i) A[m].coeffRef(i, i) += energy.anchor_weight + eps;
    solver[m].compute(A[m]);
    if (solver[m].info() != Eigen::Success) {
      throw InvalidInputError("symmetrize: stress majorization could not factor its system");
    }
  }
  // The systems share their pattern (the plane term adds to diagonal entries the edges already
  // have), so the three coordinates are solved in one pass over L: Eigen's solves, bit for bit.
  std::optional<LdltColumns> columns;
  if (SameLdltStructure(solver[0], solver[1]))
    columns.emplace(std::vector<const SparseLdlt*>{&solver[0], &solver[1], &solver[1]});
  MajorizationResult result;
  result.X = X0;
  result.energy_before = result.energy_after = energy.Evaluate(X0);
  Eigen::MatrixX3d B(n, 3);
  for (int it = 0; it < max_iterations; ++it) {
    const Eigen::MatrixX3d& Z = result.X;
    B = eps * Z;
    if (energy.anchor_weight > 0.0) B += energy.anchor_weight * energy.anchor;
    for (size_t k = 0; k < energy.edges.size(); ++k) {
      const auto [i, j] = energy.edges[k];
      const Eigen::RowVector3d diff = Z.row(i) - Z.row(j);
      const double len = diff.norm();
      if (len <= 0.0) continue;
      const Eigen::RowVector3d pull = energy.lengths[k] / len * diff;
      B.row(i) += pull;
      B.row(j) -= pull;
    }
    Eigen::MatrixX3d X(n, 3);
    if (columns) {
      columns->Solve(B, X);
    } else {
      X.col(0) = solver[0].solve(B.col(0));
      X.rightCols<2>() = solver[1].solve(B.rightCols<2>());
    }
    const double e = energy.Evaluate(X);
    ++result.iterations;
    const double decrease = result.energy_after - e;
    result.X = std::move(X);
    result.energy_after = e;
    if (decrease <= relative_tolerance * e) break;
  }
  return result;
}

}  // namespace symembed

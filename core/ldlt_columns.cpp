#include "core/ldlt_columns.h"

#include <string>
#include <utility>

#include "core/errors.h"

namespace symembed {

namespace {

// K columns interleaved in W (row i of the n x K row-major work array holds entry i of every
// column): the same operations per column as Eigen's solve, in one pass per step.
template <int K>
void Solve(const std::vector<const SparseLdlt*>& factors,
           const std::vector<Eigen::VectorXd>& inverse_diagonals,
           const Eigen::Ref<const Eigen::MatrixXd>& B, Eigen::Ref<Eigen::MatrixXd> X) {
  const SparseLdlt& first = *factors[0];
  const Eigen::SparseMatrix<double>& L0 = first.matrixL().nestedExpression();
  const int n = static_cast<int>(L0.rows());
  const int* outer = L0.outerIndexPtr();
  const int* inner = L0.innerIndexPtr();
  const double* values[K];
  const double* inverse_diagonal[K];
  for (int c = 0; c < K; ++c) {
    values[c] = factors[c]->matrixL().nestedExpression().valuePtr();
    inverse_diagonal[c] = inverse_diagonals[c].data();
  }
  const bool permuted = first.permutationP().size() > 0;
  const int* perm = permuted ? first.permutationP().indices().data() : nullptr;
  const int* perm_inv = permuted ? first.permutationPinv().indices().data() : nullptr;
  std::vector<double> w(static_cast<size_t>(n) * K);
  // dest = P b: row i of b goes to row P(i).
  for (int i = 0; i < n; ++i) {
    const int to = permuted ? perm[i] : i;
    for (int c = 0; c < K; ++c) w[static_cast<size_t>(to) * K + c] = B(i, c);
  }
  if (L0.nonZeros() > 0) {
    // Unit lower, column-major: each column's entry, unless zero, is subtracted times the
    // column of L below the diagonal from the entries below it.
    for (int i = 0; i < n; ++i) {
      double t[K];
      bool any = false;
      for (int c = 0; c < K; ++c) {
        t[c] = w[static_cast<size_t>(i) * K + c];
        any |= t[c] != 0.0;
      }
      if (!any) continue;
      int p = outer[i];
      const int end = outer[i + 1];
      while (p < end && inner[p] < i) ++p;
      if (p < end && inner[p] == i) ++p;
      for (; p < end; ++p) {
        double* row = &w[static_cast<size_t>(inner[p]) * K];
        for (int c = 0; c < K; ++c) {
          if (t[c] != 0.0) row[c] -= t[c] * values[c][p];
        }
      }
    }
  }
  // dest = D^-1 dest: Eigen multiplies by the inverted entry.
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < K; ++c) {
      w[static_cast<size_t>(i) * K + c] =
          inverse_diagonal[c][i] * w[static_cast<size_t>(i) * K + c];
    }
  }
  if (L0.nonZeros() > 0) {
    // Unit upper L^T, row by row from the last: row i of L^T is column i of L.
    for (int i = n - 1; i >= 0; --i) {
      double t[K];
      for (int c = 0; c < K; ++c) t[c] = w[static_cast<size_t>(i) * K + c];
      int p = outer[i];
      const int end = outer[i + 1];
      while (p < end && inner[p] < i) ++p;
      if (p < end && inner[p] == i) ++p;
      for (; p < end; ++p) {
        const double* row = &w[static_cast<size_t>(inner[p]) * K];
        for (int c = 0; c < K; ++c) t[c] -= values[c][p] * row[c];
      }
      for (int c = 0; c < K; ++c) w[static_cast<size_t>(i) * K + c] = t[c];
    }
  }
  // x = P^-1 dest: row i goes to row Pinv(i).
  for (int i = 0; i < n; ++i) {
    const int to = permuted ? perm_inv[i] : i;
    for (int c = 0; c < K; ++c) X(to, c) = w[static_cast<size_t>(i) * K + c];
  }
}

}  // namespace

bool SameLdltStructure(const SparseLdlt& a, const SparseLdlt& b) {
  const Eigen::SparseMatrix<double>& la = a.matrixL().nestedExpression();
  const Eigen::SparseMatrix<double>& lb = b.matrixL().nestedExpression();
  if (la.rows() != lb.rows() || la.nonZeros() != lb.nonZeros() || !la.isCompressed() ||
      !lb.isCompressed()) {
    return false;
  }
  if (a.permutationP().indices() != b.permutationP().indices()) return false;
  const int n = static_cast<int>(la.rows());
  for (int i = 0; i <= n; ++i) {
    if (la.outerIndexPtr()[i] != lb.outerIndexPtr()[i]) return false;
  }
  for (Eigen::Index p = 0; p < la.nonZeros(); ++p) {
    if (la.innerIndexPtr()[p] != lb.innerIndexPtr()[p]) return false;
  }
  return true;
}

LdltColumns::LdltColumns(std::vector<const SparseLdlt*> factors) : factors_(std::move(factors)) {
  const int k = static_cast<int>(factors_.size());
  if (k < 1 || k > 3) {
    throw InvalidInputError("LdltColumns: " + std::to_string(k) + " factors (1 to 3)");
  }
  for (const SparseLdlt* f : factors_) {
    if (f == nullptr || f->info() != Eigen::Success) {
      throw InvalidInputError("LdltColumns: a factorisation was not computed");
    }
    if (!SameLdltStructure(*factors_[0], *f)) {
      throw InvalidInputError("LdltColumns: the factorisations differ in structure");
    }
    // Eigen's solve multiplies by the diagonal's inverse, 1 / d each (vectorD() is a copy).
    inverse_diagonals_.push_back(f->vectorD().cwiseInverse());
  }
}

void LdltColumns::Solve(const Eigen::Ref<const Eigen::MatrixXd>& B,
                        Eigen::Ref<Eigen::MatrixXd> X) const {
  const int k = static_cast<int>(factors_.size());
  const Eigen::Index n = factors_[0]->matrixL().nestedExpression().rows();
  if (B.rows() != n || X.rows() != n || B.cols() != k || X.cols() != k) {
    throw InvalidInputError("LdltColumns: B and X must be " + std::to_string(n) + " x " +
                            std::to_string(k));
  }
  if (k == 1) symembed::Solve<1>(factors_, inverse_diagonals_, B, X);
  if (k == 2) symembed::Solve<2>(factors_, inverse_diagonals_, B, X);
  if (k == 3) symembed::Solve<3>(factors_, inverse_diagonals_, B, X);
}

}  // namespace symembed

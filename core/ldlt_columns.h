// Several right-hand sides solved with Eigen's simplicial LDLT factorisations in one pass.
//
// LdltColumns(factors).Solve(B, X) sets column c of X (n x k) to the solution with
// *factors[c] of column c of B, for factorisations that share their structure (SameLdltStructure:
// the same fill-reducing permutation and the same pattern of L, as the factorisations of
// matrices with one sparsity pattern have). Each column gets the operations of
// Eigen::SimplicialLDLT::solve, in their order: the permutation, the unit lower solve (skipping
// a zero entry's column), the product with the inverted diagonal, the unit upper solve and the
// inverse permutation. So the result is Eigen's, bit for bit; the columns share the passes over
// L, and the upper solve's chains of dependent subtractions, one per column, overlap. The
// factors are checked and their diagonals inverted once, for many solves.
// k is 1 to 3. Throws InvalidInputError for factors that do not share their structure or have
// not been computed successfully, and for B and X that do not fit them.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCholesky>
#include <vector>

namespace symembed {

using SparseLdlt = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;

// Whether a and b have the same permutation and the same pattern of L.
bool SameLdltStructure(const SparseLdlt& a, const SparseLdlt& b);

class LdltColumns {
 public:
  // The factors must outlive this object.
  explicit LdltColumns(std::vector<const SparseLdlt*> factors);
  void Solve(const Eigen::Ref<const Eigen::MatrixXd>& B, Eigen::Ref<Eigen::MatrixXd> X) const;

 private:
  std::vector<const SparseLdlt*> factors_;
  std::vector<Eigen::VectorXd> inverse_diagonals_;  // 1 / D of each factor, as Eigen's solve
};

}  // namespace symembed

#include "core/mds/classical_mds.h"

#include <Spectra/MatOp/DenseSymMatProd.h>
#include <Spectra/SymEigsSolver.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/errors.h"

namespace symembed {

bool ClassicalMdsOptions::IsValid(std::string* error) const {
  std::ostringstream why;
  if (dims < 1)
    why << "dims must be >= 1, got " << dims;
  else if (dense_limit < 0)
    why << "dense_limit must be >= 0, got " << dense_limit;
  else if (!(eigen_tolerance > 0.0))
    why << "eigen_tolerance must be > 0, got " << eigen_tolerance;
  else if (eigen_max_iterations < 1)
    why << "eigen_max_iterations must be >= 1, got " << eigen_max_iterations;
  if (why.str().empty()) return true;
  if (error) *error = why.str();
  return false;
}

ClassicalMdsResult ClassicalMds(const Eigen::MatrixXd& D_in, const ClassicalMdsOptions& options) {
  std::string why;
  if (!options.IsValid(&why)) throw ConfigError("ClassicalMdsOptions: " + why);
  const int n = static_cast<int>(D_in.rows());
  const int dims = options.dims;
  if (D_in.cols() != n || n < dims + 1) {
    std::ostringstream m;
    m << "ClassicalMds: distances are " << D_in.rows() << "x" << D_in.cols()
      << ", need a square matrix with more than dims = " << dims << " rows";
    throw InvalidInputError(m.str());
  }
  if (!D_in.allFinite() || (D_in.array() < 0.0).any()) {
    throw InvalidInputError("ClassicalMds: distances must be finite and non-negative");
  }
  ClassicalMdsResult result;
  Eigen::MatrixXd B = (0.5 * (D_in + D_in.transpose())).array().square().matrix();
  result.mean_squared = B.colwise().mean().transpose();
  // Double centring in place: B = -1/2 (D2 - row means - column means + grand mean).
  const double grand = result.mean_squared.mean();
  B.colwise() -= result.mean_squared;
  B.rowwise() -= result.mean_squared.transpose();
  B.array() += grand;
  B *= -0.5;

  if (n <= options.dense_limit || dims + 1 >= n) {
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(B);
    if (eig.info() != Eigen::Success) throw SolverError("ClassicalMds: eigendecomposition failed");
    // Ascending order: the top dims are the last columns, reversed.
    result.eigenvalues = eig.eigenvalues().tail(dims).reverse();
    result.eigenvectors = eig.eigenvectors().rightCols(dims).rowwise().reverse();
  } else {
    Spectra::DenseSymMatProd<double> op(B);
    const int ncv = std::min(n, std::max(2 * dims + 1, 20));
    Spectra::SymEigsSolver<Spectra::DenseSymMatProd<double>> eigs(op, dims, ncv);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, options.eigen_max_iterations,
                 options.eigen_tolerance, Spectra::SortRule::LargestAlge);
    if (eigs.info() != Spectra::CompInfo::Successful) {
      throw SolverError("ClassicalMds: Lanczos eigensolver did not converge");
    }
    result.eigenvalues = eigs.eigenvalues();
    result.eigenvectors = eigs.eigenvectors();
    result.solver_iterations = static_cast<int>(eigs.num_iterations());
  }
  const Eigen::VectorXd root = result.eigenvalues.cwiseMax(0.0).cwiseSqrt();
  result.X = result.eigenvectors * root.asDiagonal();
  result.X.rowwise() -= result.X.colwise().mean();
  return result;
}

Eigen::MatrixXd LandmarkMds(const ClassicalMdsResult& mds, const Eigen::MatrixXd& Dq,
                            const std::vector<int>& columns) {
  const int n = static_cast<int>(mds.eigenvectors.rows());
  const int dims = static_cast<int>(mds.eigenvectors.cols());
  if (Dq.rows() != n) {
    throw InvalidInputError("LandmarkMds: query distances have " + std::to_string(Dq.rows()) +
                            " rows, expected one per landmark (" + std::to_string(n) + ")");
  }
  // Pseudo-inverse transpose L#^T (n x dims): column k = v_k / sqrt(lambda_k), 0 if lambda <= 0.
  Eigen::MatrixXd Lt = mds.eigenvectors;
  for (int k = 0; k < dims; ++k) {
    const double lambda = mds.eigenvalues(k);
    Lt.col(k) *= lambda > 0.0 ? 1.0 / std::sqrt(lambda) : 0.0;
  }
  const int m = columns.empty() ? static_cast<int>(Dq.cols()) : static_cast<int>(columns.size());
  // Queries in blocks so the squared distances never need a copy of all of Dq.
  constexpr int kBlock = 256;
  Eigen::MatrixXd Y(m, dims);
  Eigen::MatrixXd S(n, kBlock);
  for (int begin = 0; begin < m; begin += kBlock) {
    const int count = std::min(kBlock, m - begin);
    for (int q = 0; q < count; ++q) {
      const int col = columns.empty() ? begin + q : columns[begin + q];
      if (col < 0 || col >= Dq.cols()) {
        throw InvalidInputError("LandmarkMds: query column " + std::to_string(col) +
                                " out of range");
      }
      S.col(q) = Dq.col(col).array().square().matrix() - mds.mean_squared;
    }
    Y.middleRows(begin, count).noalias() = -0.5 * S.leftCols(count).transpose() * Lt;
  }
  return Y;
}

}  // namespace symembed

#include "core/spectral.h"

#include <Spectra/MatOp/SparseSymMatProd.h>
#include <Spectra/SymGEigsShiftSolver.h>

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <sstream>
#include <vector>

#include "core/errors.h"

namespace symembed {

namespace {

using SpMat = Eigen::SparseMatrix<double>;

// Spectra operator y = (L - sigma M)^{-1} x with one simplicial LDL^T factorisation: L - sigma M is
// symmetric positive definite for sigma < 0 once zero-mass vertices are removed, so LDL^T is both
// faster and more robust than the LU factorisation of Spectra's own SymShiftInvert.
class ShiftedLdltSolve {
 public:
  using Scalar = double;

  ShiftedLdltSolve(const SpMat& L, const SpMat& M) : L_(L), M_(M) {}

  Eigen::Index rows() const { return L_.rows(); }
  Eigen::Index cols() const { return L_.cols(); }

  void set_shift(double sigma) {
    const SpMat A = L_ - sigma * M_;
    ldlt_.compute(A);
    if (ldlt_.info() != Eigen::Success) {
      throw SolverError("Laplace-Beltrami basis: LDL^T factorisation of L - sigma M failed");
    }
  }

  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Eigen::VectorXd> x(x_in, rows());
    Eigen::Map<Eigen::VectorXd> y(y_out, rows());
    y.noalias() = ldlt_.solve(x);
  }

 private:
  const SpMat& L_;
  const SpMat& M_;
  Eigen::SimplicialLDLT<SpMat> ldlt_;
};

// Rows and columns `keep` of A (keep[i] = new index or -1).
SpMat Restrict(const SpMat& A, const std::vector<int>& keep, int n_kept) {
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(A.nonZeros());
  for (int c = 0; c < A.outerSize(); ++c) {
    if (keep[c] < 0) continue;
    for (SpMat::InnerIterator it(A, c); it; ++it) {
      if (keep[it.row()] >= 0) triplets.emplace_back(keep[it.row()], keep[c], it.value());
    }
  }
  SpMat R(n_kept, n_kept);
  R.setFromTriplets(triplets.begin(), triplets.end());
  return R;
}

}  // namespace

bool LaplaceBasisOptions::IsValid(std::string* error) const {
  std::ostringstream out;
  if (k < 1) {
    out << "k must be >= 1, got " << k;
  } else if (!(tolerance > 0.0 && tolerance < 1.0)) {
    out << "tolerance must be in (0, 1), got " << tolerance;
  } else if (max_iterations < 1) {
    out << "max_iterations must be >= 1, got " << max_iterations;
  }
  if (out.str().empty()) return true;
  if (error != nullptr) *error = out.str();
  return false;
}

LaplaceBasis ComputeLaplaceBasis(const Surface& surface, const LaplaceBasisOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("LaplaceBasisOptions: " + error);
  const int n = surface.NumVertices();

  LaplaceBasis basis;
  basis.mass = VertexAreas(surface);
  std::vector<int> keep(n, -1);
  int n_kept = 0;
  double area = 0.0;
  for (int i = 0; i < n; ++i) {
    if (basis.mass(i) > 0.0) {
      keep[i] = n_kept++;
      area += basis.mass(i);
    }
  }
  const int k = options.k;
  if (k >= n_kept) {
    std::ostringstream out;
    out << "Laplace-Beltrami basis: k = " << k << " must be less than the number of vertices"
        << " with positive area (" << n_kept << " of " << n << ")";
    throw InvalidInputError(out.str());
  }

  const SpMat L = Restrict(CotanStiffness(surface), keep, n_kept);
  const SpMat M = Restrict(MassMatrix(surface, options.mass), keep, n_kept);

  // Eigenvalues scale as 1 / area; the first nonzero one of a unit-area sphere is 8 pi. A shift of
  // -1e-3 / area keeps L - sigma M well conditioned while leaving the low spectrum well separated
  // after the inversion nu = 1 / (lambda - sigma).
  const double sigma = -1e-3 / area;
  ShiftedLdltSolve op(L, M);
  Spectra::SparseSymMatProd<double> bop(M);
  // Lanczos from one start vector finds further copies of a repeated eigenvalue only through
  // rounding, late in the iteration, so a multiplet cut by k may be returned incomplete (seen on
  // the icosphere). A few extra eigenpairs, dropped at the end, keep the first k complete.
  const int nev = std::min(n_kept - 1, k + std::max(8, k / 10));
  const int ncv = std::min(n_kept, std::max(2 * nev + 1, nev + 20));
  try {
    Spectra::SymGEigsShiftSolver<ShiftedLdltSolve, Spectra::SparseSymMatProd<double>,
                                 Spectra::GEigsMode::ShiftInvert>
        solver(op, bop, nev, ncv, sigma);
    solver.init();
    solver.compute(Spectra::SortRule::LargestMagn, options.max_iterations, options.tolerance,
                   Spectra::SortRule::SmallestAlge);
    if (solver.info() != Spectra::CompInfo::Successful) {
      std::ostringstream out;
      out << "Laplace-Beltrami basis: the Lanczos iteration did not converge (k = " << nev << ", "
          << solver.num_iterations() << " restarts)";
      throw SolverError(out.str());
    }
    basis.evals = solver.eigenvalues().head(k);
    const Eigen::MatrixXd evecs = solver.eigenvectors().leftCols(k);
    basis.evecs = Eigen::MatrixXd::Zero(n, k);
    for (int i = 0; i < n; ++i) {
      if (keep[i] >= 0) basis.evecs.row(i) = evecs.row(keep[i]);
    }
  } catch (const std::invalid_argument& e) {
    throw SolverError(std::string("Laplace-Beltrami basis: ") + e.what());
  } catch (const std::logic_error& e) {
    throw SolverError(std::string("Laplace-Beltrami basis: ") + e.what());
  }
  // Fix the arbitrary signs (largest-magnitude entry positive) so that equal inputs give equal
  // bases whatever the iteration order.
  for (int j = 0; j < k; ++j) {
    Eigen::Index arg = 0;
    basis.evecs.col(j).cwiseAbs().maxCoeff(&arg);
    if (basis.evecs(arg, j) < 0.0) basis.evecs.col(j) *= -1.0;
  }
  return basis;
}

void PositiveEigenvalueRange(const Eigen::VectorXd& evals, double* lambda_1, double* lambda_max) {
  SYMEMBED_CHECK(evals.size() > 0, "no eigenvalues");
  *lambda_max = evals.maxCoeff();
  *lambda_1 = *lambda_max;
  for (int i = 0; i < evals.size(); ++i) {
    if (evals(i) > 1e-8 * *lambda_max) *lambda_1 = std::min(*lambda_1, evals(i));
  }
}

void LeadingEigenpairs(const LaplaceBasis& basis, int k, LaplaceBasis* out) {
  SYMEMBED_CHECK(out != nullptr, "out is null");
  const int stored = basis.NumEigenpairs();
  const int n = basis.NumVertices();
  if (basis.evecs.cols() != stored || basis.mass.size() != n || stored < std::max(k, 0)) {
    std::ostringstream message;
    message << "the Laplace-Beltrami basis is inconsistent or holds fewer than " << k
            << " eigenpairs (evals " << stored << ", evecs " << basis.evecs.rows() << "x"
            << basis.evecs.cols() << ", mass " << basis.mass.size() << ")";
    throw InvalidInputError(message.str());
  }
  const int used = k < 0 ? stored : k;
  out->evals = basis.evals.head(used);
  out->evecs = basis.evecs.leftCols(used);
  out->mass = basis.mass;
}

LaplaceBasis LeadingEigenpairs(const LaplaceBasis& basis, int k) {
  LaplaceBasis out;
  LeadingEigenpairs(basis, k, &out);
  return out;
}

}  // namespace symembed

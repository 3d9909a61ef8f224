#include "core/procrustes.h"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>
#include <string>

#include "core/errors.h"

namespace symembed {

ProcrustesFit FitProcrustes(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y,
                            const ProcrustesOptions& options) {
  if (X.rows() != Y.rows() || X.cols() != Y.cols() || X.rows() < 1 || X.cols() < 1) {
    throw InvalidInputError("FitProcrustes: point sets of shapes " + std::to_string(X.rows()) +
                            "x" + std::to_string(X.cols()) + " and " + std::to_string(Y.rows()) +
                            "x" + std::to_string(Y.cols()) + " do not match");
  }
  ProcrustesFit fit;
  fit.source_mean = X.colwise().mean();
  fit.target_mean = Y.colwise().mean();
  const Eigen::MatrixXd Xc = X.rowwise() - fit.source_mean;
  const Eigen::MatrixXd Yc = Y.rowwise() - fit.target_mean;
  // max_R tr(R^T Xc^T Yc) over orthogonal R: with Xc^T Yc = U S V^T, R = U V^T; for a proper
  // rotation the smallest singular direction is flipped when det(U V^T) < 0.
  const Eigen::MatrixXd M = Xc.transpose() * Yc;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::MatrixXd& U = svd.matrixU();
  const Eigen::MatrixXd& Vm = svd.matrixV();
  const Eigen::VectorXd& s = svd.singularValues();
  const double det_uv = (U * Vm.transpose()).determinant();
  Eigen::VectorXd signs = Eigen::VectorXd::Ones(s.size());
  if (!options.allow_reflection && det_uv < 0) signs(s.size() - 1) = -1.0;
  fit.R = U * signs.asDiagonal() * Vm.transpose();
  fit.det_sign = fit.R.determinant() < 0 ? -1 : 1;
  fit.conditioning = s(0) > 0 ? s(s.size() - 1) / s(0) : 0.0;
  const double xx = Xc.squaredNorm();
  if (options.allow_scale && xx > 0) fit.scale = std::max(0.0, signs.dot(s)) / xx;
  const Eigen::MatrixXd residual = fit.scale * Xc * fit.R - Yc;
  fit.rms_residual = std::sqrt(residual.squaredNorm() / static_cast<double>(X.rows()));
  return fit;
}

Eigen::MatrixXd ApplyProcrustes(const ProcrustesFit& fit, const Eigen::MatrixXd& X) {
  SYMEMBED_CHECK(X.cols() == fit.R.rows(), "ApplyProcrustes: " << X.cols() << " columns, fit is "
                                                               << fit.R.rows() << "-dimensional");
  return ((fit.scale * (X.rowwise() - fit.source_mean) * fit.R).rowwise() + fit.target_mean).eval();
}

int ProcrustesReflection(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y) {
  return FitProcrustes(X, Y).det_sign;
}

double SelfMapDisplacement(const Eigen::MatrixXd& P, const std::vector<int>& sigma) {
  if (sigma.empty() || sigma.size() != static_cast<size_t>(P.rows())) return -1.0;
  const double size = RmsRadius(P);
  if (!(size > 0.0)) return -1.0;
  double sum = 0.0;
  for (size_t i = 0; i < sigma.size(); ++i) {
    if (sigma[i] < 0 || sigma[i] >= P.rows()) return -1.0;
    sum += (P.row(i) - P.row(sigma[i])).norm();
  }
  return sum / sigma.size() / size;
}

}  // namespace symembed

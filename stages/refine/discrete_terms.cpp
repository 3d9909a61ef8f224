#include "stages/refine/discrete_terms.h"

#include <Eigen/QR>
#include <cmath>
#include <sstream>

#include "core/errors.h"

namespace symembed {

namespace {

void CheckSquare(const BasisRef& X, const BasisRef& Y, const Eigen::MatrixXd& C, const char* term) {
  SYMEMBED_CHECK(C.rows() == X.cols() && C.cols() == Y.cols(),
                 term << " term: the functional map is " << C.rows() << " x " << C.cols()
                      << " for bases of " << X.cols() << " and " << Y.cols() << " columns");
}

}  // namespace

TermRows OrthogonalityRows(const BasisRef& X, const BasisRef& Y, const Eigen::MatrixXd& C_xy) {
  CheckSquare(X, Y, C_xy, "orthogonality");
  return {X, Y * C_xy.transpose()};
}

TermRows BijectivityRows(const BasisRef& X, const BasisRef& Y, const Eigen::MatrixXd& C_yx) {
  SYMEMBED_CHECK(C_yx.rows() == Y.cols() && C_yx.cols() == X.cols(),
                 "bijectivity term: the inverse functional map is "
                     << C_yx.rows() << " x " << C_yx.cols() << " for bases of " << X.cols()
                     << " and " << Y.cols() << " columns");
  return {X, Y * C_yx};
}

TermRows ProperRows(const BasisRef& X, const BasisRef& Y, const Eigen::MatrixXd& C_xy) {
  CheckSquare(X, Y, C_xy, "proper");
  return {X * C_xy, Y};
}

TermRows LaplacianRows(const BasisRef& X, const BasisRef& Y, const Eigen::VectorXd& lambda_x,
                       const Eigen::VectorXd& lambda_y, const Eigen::MatrixXd& C_xy) {
  CheckSquare(X, Y, C_xy, "Laplacian");
  SYMEMBED_CHECK(lambda_x.size() == X.cols() && lambda_y.size() == Y.cols(),
                 "Laplacian term: " << lambda_x.size() << " and " << lambda_y.size()
                                    << " eigenvalues for bases of " << X.cols() << " and "
                                    << Y.cols() << " columns");
  return {X * lambda_x.asDiagonal(), Y * lambda_y.asDiagonal() * C_xy.transpose()};
}

TermRows DescriptorRows(const BasisRef& X, const BasisRef& Y, const Eigen::MatrixXd& A_x,
                        const Eigen::MatrixXd& A_y) {
  SYMEMBED_CHECK(A_x.rows() == X.cols() && A_y.rows() == Y.cols() && A_x.cols() == A_y.cols(),
                 "descriptor term: coefficients "
                     << A_x.rows() << " x " << A_x.cols() << " and " << A_y.rows() << " x "
                     << A_y.cols() << " for bases of " << X.cols() << " and " << Y.cols()
                     << " columns");
  return {X * A_x, Y * A_y};
}

TermRows EmbeddingRows(const Eigen::MatrixXd& Z_x, const Eigen::MatrixXd& Z_y) {
  SYMEMBED_CHECK(Z_x.cols() == Z_y.cols(), "embedding term: points of " << Z_x.cols() << " and "
                                                                        << Z_y.cols()
                                                                        << " coordinates");
  return {Z_x, Z_y};
}

void ScaledEigenvalues(const Eigen::VectorXd& evals_x, const Eigen::VectorXd& evals_y, int k,
                       Eigen::VectorXd* lambda_x, Eigen::VectorXd* lambda_y) {
  if (k < 1 || evals_x.size() < k || evals_y.size() < k) {
    std::ostringstream out;
    out << "Laplacian term: " << k << " eigenvalues asked of spectra of " << evals_x.size()
        << " and " << evals_y.size();
    throw InvalidInputError(out.str());
  }
  const double scale = 0.5 * (evals_x(k - 1) + evals_y(k - 1));
  if (!(scale > 0.0) || !std::isfinite(scale)) {
    std::ostringstream out;
    out << "Laplacian term: the " << k << "-th eigenvalues (" << evals_x(k - 1) << ", "
        << evals_y(k - 1) << ") give no positive scale";
    throw InvalidInputError(out.str());
  }
  *lambda_x = evals_x.head(k) / scale;
  *lambda_y = evals_y.head(k) / scale;
}

double TermEnergy(const TermRows& rows, const std::vector<int>& map, const Eigen::VectorXd& w) {
  SYMEMBED_CHECK(static_cast<Eigen::Index>(map.size()) == rows.query.rows() &&
                     w.size() == rows.query.rows() && rows.query.cols() == rows.points.cols(),
                 "term energy: " << rows.query.rows() << " query rows, " << map.size()
                                 << " map entries, " << w.size() << " weights");
  double energy = 0.0;
  for (size_t r = 0; r < map.size(); ++r) {
    SYMEMBED_CHECK(map[r] >= 0 && map[r] < rows.points.rows(),
                   "term energy: map entry " << map[r] << " out of range");
    energy += w(r) * (rows.query.row(r) - rows.points.row(map[r])).squaredNorm();
  }
  return energy;
}

TermRows StackTerms(const std::vector<TermRows>& terms, const std::vector<double>& weights) {
  SYMEMBED_CHECK(terms.size() == weights.size() && !terms.empty(),
                 "stacked terms: " << terms.size() << " terms, " << weights.size() << " weights");
  Eigen::Index cols = 0, queries = -1, points = -1;
  for (size_t t = 0; t < terms.size(); ++t) {
    SYMEMBED_CHECK(weights[t] >= 0.0, "stacked terms: negative weight " << weights[t]);
    if (weights[t] == 0.0) continue;
    if (queries < 0) {
      queries = terms[t].query.rows();
      points = terms[t].points.rows();
    }
    SYMEMBED_CHECK(terms[t].query.rows() == queries && terms[t].points.rows() == points &&
                       terms[t].query.cols() == terms[t].points.cols(),
                   "stacked terms: term " << t << " has other rows than the first");
    cols += terms[t].query.cols();
  }
  SYMEMBED_CHECK(cols > 0, "stacked terms: no term has a positive weight");
  TermRows out{Eigen::MatrixXd(queries, cols), Eigen::MatrixXd(points, cols)};
  Eigen::Index at = 0;
  for (size_t t = 0; t < terms.size(); ++t) {
    if (weights[t] == 0.0) continue;
    const double s = std::sqrt(weights[t]);
    const Eigen::Index c = terms[t].query.cols();
    out.query.middleCols(at, c) = s * terms[t].query;
    out.points.middleCols(at, c) = s * terms[t].points;
    at += c;
  }
  return out;
}

ReducedTerms ReduceTerms(const BasisRef& X, const BasisRef& Y, const TermRows& maps,
                         const Eigen::MatrixXd* Z_x, const Eigen::MatrixXd* Z_y,
                         double embedding_weight) {
  const Eigen::Index k = X.cols();
  const Eigen::MatrixXd& L_x = maps.query;
  const Eigen::MatrixXd& L_y = maps.points;
  const Eigen::Index cols = L_x.cols();
  SYMEMBED_CHECK(
      Y.cols() == k && L_x.rows() == k && L_y.rows() == k && L_y.cols() == cols && cols >= k,
      "reduced terms: maps " << L_x.rows() << " x " << cols << " and " << L_y.rows() << " x "
                             << L_y.cols() << " for bases of " << k << " and " << Y.cols()
                             << " columns");
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(L_y.transpose());
  const Eigen::MatrixXd Q = qr.householderQ() * Eigen::MatrixXd::Identity(cols, k);
  const Eigen::MatrixXd R_t = L_y * Q;  // R^T: L_y = R^T Q^T
  const Eigen::MatrixXd M = L_x * Q;
  const Eigen::MatrixXd G = L_x * L_x.transpose() - M * M.transpose();
  const bool embedded = Z_x != nullptr && Z_y != nullptr && embedding_weight > 0.0;
  const Eigen::Index d = embedded ? Z_x->cols() : 0;
  if (embedded) {
    SYMEMBED_CHECK(Z_y->cols() == d && Z_x->rows() == X.rows() && Z_y->rows() == Y.rows(),
                   "reduced terms: embedding points do not match the basis rows");
  }
  ReducedTerms out;
  out.rows.query.resize(X.rows(), k + d);
  out.rows.points.resize(Y.rows(), k + d);
  out.rows.query.leftCols(k).noalias() = X * M;
  out.rows.points.leftCols(k).noalias() = Y * R_t;
  if (embedded) {
    const double s = std::sqrt(embedding_weight);
    out.rows.query.rightCols(d) = s * *Z_x;
    out.rows.points.rightCols(d) = s * *Z_y;
  }
  out.G = G;
  return out;
}

double BijectivityDefect(const Eigen::MatrixXd& C_xy, const Eigen::MatrixXd& C_yx) {
  SYMEMBED_CHECK(C_xy.cols() == C_yx.rows() && C_xy.rows() == C_yx.cols(),
                 "bijectivity defect: maps of " << C_xy.rows() << " x " << C_xy.cols() << " and "
                                                << C_yx.rows() << " x " << C_yx.cols());
  const Eigen::Index k = C_xy.rows();
  return (C_xy * C_yx - Eigen::MatrixXd::Identity(k, k)).squaredNorm() / k;
}

double CommutativityDefect(const Eigen::MatrixXd& C_xy, const Eigen::VectorXd& lambda_x,
                           const Eigen::VectorXd& lambda_y) {
  SYMEMBED_CHECK(lambda_x.size() == C_xy.rows() && lambda_y.size() == C_xy.cols(),
                 "commutativity defect: eigenvalues do not match the map");
  return (C_xy * lambda_y.asDiagonal() - lambda_x.asDiagonal() * C_xy).squaredNorm() / C_xy.rows();
}

}  // namespace symembed

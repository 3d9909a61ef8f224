#include "core/fmap/functional_map.h"

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <algorithm>
#include <limits>
#include <sstream>

#include "core/errors.h"
#include "core/fmap/spectral_knn.h"

namespace symembed {

namespace {

// The weights w(source_ids[r]) of the pairs, after checking the ids against Phi_s.
Eigen::VectorXd PairWeights(const BasisRef& Phi_s, const std::vector<int>& source_ids,
                            const Eigen::VectorXd& weights) {
  if (weights.size() != Phi_s.rows()) {
    throw InvalidInputError("functional map: weights must have one entry per source vertex");
  }
  Eigen::VectorXd w(source_ids.size());
  for (size_t r = 0; r < source_ids.size(); ++r) {
    const int i = source_ids[r];
    if (i < 0 || i >= Phi_s.rows()) {
      std::ostringstream out;
      out << "functional map: source id " << i << " of pair " << r << " out of range";
      throw InvalidInputError(out.str());
    }
    w(r) = weights(i);
  }
  return w;
}

// The rows `ids` (in range) of the first `cols` columns of Phi (all by default), gathered column
// by column: each column of a #V x k basis is contiguous, row by row would touch k cache lines
// per row.
Eigen::MatrixXd Rows(const BasisRef& Phi, const std::vector<int>& ids, int cols = -1) {
  Eigen::MatrixXd A(ids.size(), cols < 0 ? Phi.cols() : cols);
  for (int c = 0; c < A.cols(); ++c) {
    const double* column = Phi.col(c).data();
    for (size_t r = 0; r < ids.size(); ++r) A(r, c) = column[ids[r]];
  }
  return A;
}

// The pairs' weights (PairWeights), after checking the target ids against Phi_t.
Eigen::VectorXd CheckedPairWeights(const BasisRef& Phi_s, const BasisRef& Phi_t,
                                   const std::vector<int>& source_ids,
                                   const std::vector<int>& target_ids,
                                   const Eigen::VectorXd& weights) {
  if (target_ids.size() != source_ids.size()) {
    throw InvalidInputError("functional map: source and target id lists differ in length");
  }
  Eigen::VectorXd w = PairWeights(Phi_s, source_ids, weights);
  for (size_t r = 0; r < target_ids.size(); ++r) {
    const int j = target_ids[r];
    if (j < 0 || j >= Phi_t.rows()) {
      std::ostringstream out;
      out << "functional map: pair " << r << " (" << source_ids[r] << " -> " << j
          << ") out of range";
      throw InvalidInputError(out.str());
    }
  }
  return w;
}

// A^T W B for gathered rows A, B and the pairs' weights w.
Eigen::MatrixXd WeightedCross(const BasisRef& A, const BasisRef& B, const Eigen::VectorXd& w) {
  return (w.asDiagonal() * A).transpose() * B;
}

}  // namespace

Eigen::MatrixXd WeightedGram(const BasisRef& A, const Eigen::VectorXd& w) {
  SYMEMBED_CHECK(w.size() == A.rows(), "weighted Gram: " << A.rows() << " rows, " << w.size()
                                                         << " weights");
  return WeightedCross(A, A, w);
}

Eigen::MatrixXd FitFunctionalMap(const BasisRef& Phi_s, const BasisRef& Phi_t,
                                 const std::vector<int>& source_ids,
                                 const std::vector<int>& target_ids,
                                 const Eigen::VectorXd& weights, const Eigen::MatrixXd* gram) {
  const Eigen::VectorXd w = CheckedPairWeights(Phi_s, Phi_t, source_ids, target_ids, weights);
  return FitFunctionalMapFromRows(Rows(Phi_s, source_ids), Rows(Phi_t, target_ids), w, gram);
}

Eigen::MatrixXd FitFunctionalMapFromRows(const BasisRef& A, const BasisRef& B,
                                         const Eigen::VectorXd& w, const Eigen::MatrixXd* gram) {
  const int ks = static_cast<int>(A.cols());
  SYMEMBED_CHECK(A.rows() == B.rows() && w.size() == A.rows(),
                 "functional map: " << A.rows() << " source rows, " << B.rows()
                                    << " target rows, " << w.size() << " weights");
  SYMEMBED_CHECK(gram == nullptr || (gram->rows() >= ks && gram->cols() >= ks),
                 "functional map: the Gram matrix is smaller than the basis");
  const Eigen::MatrixXd AtWB = WeightedCross(A, B, w);
  const Eigen::MatrixXd AtWA =
      gram != nullptr ? Eigen::MatrixXd(gram->topLeftCorner(ks, ks)) : WeightedGram(A, w);
  // For the dense map with mass weights A^T W A = I; for a sample it is near I when the sample
  // covers the surface. LDL^T with a pivot check detects too small a sample.
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(AtWA);
  const double max_pivot = ldlt.vectorD().cwiseAbs().maxCoeff();
  if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 1e-10 * max_pivot)) {
    std::ostringstream out;
    out << "functional map: the " << A.rows() << " points do not determine a " << ks
        << "-dimensional basis (singular normal equations)";
    throw InvalidInputError(out.str());
  }
  return ldlt.solve(AtWB);
}

Eigen::MatrixXd BasisRows(const BasisRef& Phi, const std::vector<int>& ids, int cols) {
  for (size_t r = 0; r < ids.size(); ++r) {
    if (ids[r] < 0 || ids[r] >= Phi.rows()) {
      std::ostringstream out;
      out << "basis rows: id " << ids[r] << " (entry " << r << ") out of range 0.."
          << Phi.rows() - 1;
      throw InvalidInputError(out.str());
    }
  }
  SYMEMBED_CHECK(cols <= Phi.cols(), "basis rows: " << cols << " columns of " << Phi.cols());
  return Rows(Phi, ids, cols);
}

Eigen::MatrixXd FitOrthogonalFunctionalMap(const BasisRef& Phi_s, const BasisRef& Phi_t,
                                           const std::vector<int>& source_ids,
                                           const std::vector<int>& target_ids,
                                           const Eigen::VectorXd& weights) {
  SYMEMBED_CHECK(Phi_s.cols() == Phi_t.cols(), "orthogonal functional map needs ks == kt");
  const Eigen::VectorXd w = CheckedPairWeights(Phi_s, Phi_t, source_ids, target_ids, weights);
  const Eigen::MatrixXd AtWB =
      WeightedCross(Rows(Phi_s, source_ids), Rows(Phi_t, target_ids), w);
  // min ||A C - B||_W over orthogonal C = max trace(C^T A^T W B): C = U V^T.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(AtWB, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

std::vector<int> PointMapFromFunctionalMap(const Eigen::MatrixXd& Phi_s,
                                           const Eigen::MatrixXd& Phi_t,
                                           const Eigen::VectorXd& mass_t, const Eigen::MatrixXd& C,
                                           const std::vector<int>& source_ids,
                                           std::vector<double>* sq_dist,
                                           const std::vector<int>& target_ids) {
  const int ks = static_cast<int>(C.rows()), kt = static_cast<int>(C.cols());
  SYMEMBED_CHECK(ks <= Phi_s.cols() && kt <= Phi_t.cols(),
                 "C is " << ks << " x " << kt << " for bases of " << Phi_s.cols() << " and "
                         << Phi_t.cols() << " columns");
  SYMEMBED_CHECK(mass_t.size() == Phi_t.rows(), "mass_t must have one entry per target vertex");
  for (const int i : source_ids) {
    SYMEMBED_CHECK(i >= 0 && i < Phi_s.rows(), "source id " << i << " out of range");
  }
  const std::vector<int> targets = MatchableTargets(mass_t, target_ids);
  return NearestUnderMap(Rows(Phi_s, source_ids, ks), Rows(Phi_t, targets, kt), targets, C,
                         sq_dist);
}

std::vector<int> MatchableTargets(const Eigen::VectorXd& mass_t,
                                  const std::vector<int>& target_ids) {
  const bool every_vertex = target_ids.empty();
  const int candidates = every_vertex ? static_cast<int>(mass_t.size())
                                      : static_cast<int>(target_ids.size());
  std::vector<int> ids;
  for (int r = 0; r < candidates; ++r) {
    const int j = every_vertex ? r : target_ids[r];
    SYMEMBED_CHECK(j >= 0 && j < mass_t.size(), "target id " << j << " out of range");
    if (mass_t(j) > 0.0) ids.push_back(j);
  }
  if (ids.empty()) throw InvalidInputError("target surface has no vertex with positive area");
  return ids;
}

std::vector<int> NearestUnderMap(const BasisRef& Q, const BasisRef& P,
                                 const std::vector<int>& targets, const Eigen::MatrixXd& C,
                                 std::vector<double>* sq_dist, const BasisRef& target_side,
                                 const BasisRef& query_side) {
  SYMEMBED_CHECK(Q.cols() == C.rows() && P.cols() == C.cols() &&
                     P.rows() == static_cast<Eigen::Index>(targets.size()),
                 "nearest under a map: C is " << C.rows() << " x " << C.cols() << ", queries "
                                              << Q.cols() << " columns, " << P.rows() << " x "
                                              << P.cols() << " target rows for " << targets.size()
                                              << " targets");
  std::vector<int> nearest;
  const Eigen::Index m = target_side.cols();
  if (m == 0 && query_side.cols() == 0) {
    const Eigen::MatrixXd points = P * C.transpose();
    const SpectralNearest tree(points, targets);
    tree.Query(Q, &nearest, sq_dist);
    return nearest;
  }
  SYMEMBED_CHECK(
      query_side.cols() == m && target_side.rows() == P.rows() && query_side.rows() == Q.rows(),
      "nearest under a map: side columns " << target_side.rows() << " x " << m
                                           << " for the targets, " << query_side.rows() << " x "
                                           << query_side.cols() << " for the queries");
  Eigen::MatrixXd points(P.rows(), C.rows() + m), queries(Q.rows(), C.rows() + m);
  points.leftCols(C.rows()) = P * C.transpose();
  points.rightCols(m) = target_side;
  queries.leftCols(C.rows()) = Q;
  queries.rightCols(m) = query_side;
  const SpectralNearest tree(points, targets);
  tree.Query(queries, &nearest, sq_dist);
  return nearest;
}

double OrthogonalityDefect(const Eigen::MatrixXd& C) {
  const int k = static_cast<int>(C.cols());
  return (C.transpose() * C - Eigen::MatrixXd::Identity(k, k)).squaredNorm() / k;
}

std::vector<int> EuclideanFarthestPoints(const Eigen::MatrixX3d& V, int count,
                                         const std::vector<bool>& keep) {
  const int n = static_cast<int>(V.rows());
  SYMEMBED_CHECK(keep.empty() || static_cast<int>(keep.size()) == n, "keep has wrong size");
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  int next = -1;
  for (int i = 0; i < n && next < 0; ++i) {
    if (keep.empty() || keep[i]) next = i;
  }
  std::vector<int> samples;
  while (next >= 0 && static_cast<int>(samples.size()) < count) {
    samples.push_back(next);
    const Eigen::RowVector3d p = V.row(next);
    int arg = -1;
    double best = 0.0;
    for (int i = 0; i < n; ++i) {
      if (!keep.empty() && !keep[i]) continue;
      dist[i] = std::min(dist[i], (V.row(i) - p).squaredNorm());
      if (dist[i] > best) {
        best = dist[i];
        arg = i;
      }
    }
    next = arg;  // -1 once every kept vertex is a sample (all distances 0)
  }
  return samples;
}

void CheckPointMap(const std::vector<int>& map, int num_source, int num_target) {
  if (static_cast<int>(map.size()) != num_source) {
    std::ostringstream out;
    out << "point map has " << map.size() << " entries for " << num_source << " source vertices";
    throw InvalidInputError(out.str());
  }
  for (int i = 0; i < num_source; ++i) {
    if (map[i] < 0 || map[i] >= num_target) {
      std::ostringstream out;
      out << "point map entry " << i << " = " << map[i] << " is not a target vertex (0.."
          << num_target - 1 << ")";
      throw InvalidInputError(out.str());
    }
  }
}

}  // namespace symembed

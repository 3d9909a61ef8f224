// Inputs shared by the embedding tests: point sets with exactly Euclidean distances.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <random>

#include "core/mesh.h"

namespace symembed::testing {

// n points uniform in the box [-1, 1] x [-0.6, 0.6] x [-0.3, 0.3] (distinct extents, so the
// principal axes are well separated and the set is far from planar).
inline Eigen::MatrixXd BoxPoints(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd P(n, 3);
  for (int i = 0; i < n; ++i) P.row(i) << u(rng), 0.6 * u(rng), 0.3 * u(rng);
  return P;
}

// Euclidean distances between the rows of P (p x d) and Q (q x d): p x q.
inline Eigen::MatrixXd EuclideanDistances(const Eigen::MatrixXd& P, const Eigen::MatrixXd& Q) {
  Eigen::MatrixXd D(P.rows(), Q.rows());
  for (int j = 0; j < Q.rows(); ++j) D.col(j) = (P.rowwise() - Q.row(j)).rowwise().norm();
  return D;
}

// Sign of det(Xc^T Yc) for centred X, Y (n x 3): the sign of the optimal orthogonal Procrustes
// fit computed without an SVD (det(U S V^T) has the sign of det(U V^T) since S > 0).
inline int CrossCovarianceDetSign(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y) {
  const Eigen::MatrixXd Xc = X.rowwise() - X.colwise().mean();
  const Eigen::MatrixXd Yc = Y.rowwise() - Y.colwise().mean();
  return (Xc.transpose() * Yc).determinant() < 0 ? -1 : 1;
}

}  // namespace symembed::testing

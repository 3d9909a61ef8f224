// Orthogonal Procrustes analysis: the rigid motion (optionally with a uniform scale) that best
// maps one point set onto another in the least-squares sense.
//
// [Schoenemann 1966] A generalized solution of the orthogonal Procrustes problem.
// [Gower & Dijksterhuis 2004] Procrustes Problems.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace symembed {

// Root mean square distance of the rows of P (points as rows) from their centroid; 0 without
// rows. The size that makes point-set measures scale-free.
template <typename Derived>
double RmsRadius(const Eigen::MatrixBase<Derived>& P) {
  if (P.rows() == 0) return 0.0;
  const Eigen::Matrix<double, 1, Derived::ColsAtCompileTime> c = P.colwise().mean();
  return std::sqrt((P.rowwise() - c).rowwise().squaredNorm().mean());
}

// The mean distance between each row of P (points as rows) and the row sigma names as its image,
// over RmsRadius(P): how far a self map of the point set moves its points, scale-free. -1 when
// sigma does not give every row an image among P's rows or P has no extent.
double SelfMapDisplacement(const Eigen::MatrixXd& P, const std::vector<int>& sigma);

struct ProcrustesOptions {
  // Allow improper orthogonal matrices (det -1). When false, R is a proper rotation.
  bool allow_reflection = true;
  // Fit a uniform scale s > 0 as well (otherwise s = 1).
  bool allow_scale = false;
};

// The fit Y ~ s * (X - source_mean) * R + target_mean, points as rows.
struct ProcrustesFit {
  Eigen::MatrixXd R;               // d x d orthogonal
  Eigen::RowVectorXd source_mean;  // 1 x d
  Eigen::RowVectorXd target_mean;  // 1 x d
  double scale = 1.0;
  double rms_residual = 0.0;  // sqrt(mean_i ||fitted_i - y_i||^2), in Y's units
  int det_sign = 1;           // sign of det(R): -1 when the fit needs a reflection
  // Smallest singular value of the cross-covariance over the largest: near 0 when X or Y is
  // (nearly) contained in a lower-dimensional subspace, so the sign of det(R) is ill-defined.
  double conditioning = 0.0;
};

// X: n x d source points, Y: n x d target points (same row order), n >= 1, 1 <= d.
// Throws InvalidInputError on mismatched shapes.
ProcrustesFit FitProcrustes(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y,
                            const ProcrustesOptions& options = {});

// s * (X - source_mean) * R + target_mean for any point set X (m x d).
Eigen::MatrixXd ApplyProcrustes(const ProcrustesFit& fit, const Eigen::MatrixXd& X);

// Sign of det of the best orthogonal (reflections allowed) fit from X to Y: +1 when Y is
// related to X by a proper motion, -1 when by a reflection.
int ProcrustesReflection(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y);

}  // namespace symembed

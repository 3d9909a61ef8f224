#include "core/laplacian.h"

#include <Eigen/Geometry>
#include <vector>

namespace symembed {

Eigen::SparseMatrix<double> CotanStiffness(const Surface& s) {
  const int n = s.NumVertices();
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(s.F.rows() * 12);
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      // The angle at corner k is opposite edge (i, j).
      const int c = s.F(f, k), i = s.F(f, (k + 1) % 3), j = s.F(f, (k + 2) % 3);
      const Eigen::Vector3d u = s.V.row(i) - s.V.row(c);
      const Eigen::Vector3d v = s.V.row(j) - s.V.row(c);
      const double cross = u.cross(v).norm();
      // A degenerate triangle contributes nothing rather than an infinite weight.
      const double w = cross > 1e-300 ? 0.5 * u.dot(v) / cross : 0.0;
      triplets.emplace_back(i, j, -w);
      triplets.emplace_back(j, i, -w);
      triplets.emplace_back(i, i, w);
      triplets.emplace_back(j, j, w);
    }
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(triplets.begin(), triplets.end());
  return L;
}

Eigen::MatrixX3d VertexNormals(const Surface& s) { return VertexNormals(s.V, s.F); }

Eigen::MatrixX3d VertexNormals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  Eigen::MatrixX3d N = Eigen::MatrixX3d::Zero(V.rows(), 3);
  for (int f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();  // length = 2 * area
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (int i = 0; i < N.rows(); ++i) {
    const double len = N.row(i).norm();
    if (len > 0.0) N.row(i) /= len;
  }
  return N;
}

Eigen::VectorXd VertexAreas(const Surface& s) {
  const Eigen::VectorXd face_areas = FaceAreas(s);
  Eigen::VectorXd a = Eigen::VectorXd::Zero(s.NumVertices());
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) a(s.F(f, k)) += face_areas(f) / 3.0;
  }
  return a;
}

Eigen::SparseMatrix<double> MassMatrix(const Surface& s, MassType type) {
  const int n = s.NumVertices();
  std::vector<Eigen::Triplet<double>> triplets;
  if (type == MassType::kLumped) {
    const Eigen::VectorXd a = VertexAreas(s);
    for (int i = 0; i < n; ++i) triplets.emplace_back(i, i, a(i));
  } else {
    const Eigen::VectorXd face_areas = FaceAreas(s);
    for (int f = 0; f < s.F.rows(); ++f) {
      for (int a = 0; a < 3; ++a) {
        for (int b = 0; b < 3; ++b) {
          triplets.emplace_back(s.F(f, a), s.F(f, b), face_areas(f) / (a == b ? 6.0 : 12.0));
        }
      }
    }
  }
  Eigen::SparseMatrix<double> M(n, n);
  M.setFromTriplets(triplets.begin(), triplets.end());
  return M;
}

}  // namespace symembed

#include "core/intrinsic_delaunay.h"

#include <gtest/gtest.h>

#include "core/primitives.h"

namespace symembed {
namespace {

// A flat grid sheared so that half of its triangles are strongly obtuse (non-Delaunay).
Surface ShearedGrid(int n) {
  Surface s = GridMesh(n, n);
  for (int v = 0; v < s.NumVertices(); ++v) s.V(v, 0) += 2.0 * s.V(v, 1);
  return s;
}

TEST(IntrinsicDelaunay, FlipsUntilEveryCotanWeightIsNonNegative) {
  const Surface s = ShearedGrid(15);
  const IntrinsicTriangulation plain = IntrinsicFromSurface(s);
  const IntrinsicTriangulation del = IntrinsicDelaunay(s);
  EXPECT_EQ(plain.flips, 0);
  EXPECT_GT(del.flips, 0);
  EXPECT_EQ(del.F.rows(), s.F.rows());
  // Flips keep the metric: same total area (flat here, so exactly the planar area).
  EXPECT_NEAR(IntrinsicFaceAreas(del).sum(), TotalArea(s), 1e-12);
  const Eigen::SparseMatrix<double> K0 = IntrinsicCotanStiffness(plain, s.NumVertices());
  const Eigen::SparseMatrix<double> K = IntrinsicCotanStiffness(del, s.NumVertices());
  // Weights of interior edges (an edge with an interior endpoint is interior); boundary edges
  // carry the single cotangent of an angle that may stay obtuse.
  auto interior = [](int v) { return v % 15 > 0 && v % 15 < 14 && v / 15 > 0 && v / 15 < 14; };
  auto min_interior_weight = [&](const Eigen::SparseMatrix<double>& A) {
    double w = 0.0;
    for (int c = 0; c < A.outerSize(); ++c) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
        if (it.row() != it.col() && (interior(it.row()) || interior(it.col()))) {
          w = std::min(w, -it.value());
        }
      }
    }
    return w;
  };
  EXPECT_LT(min_interior_weight(K0), -0.1);
  EXPECT_GE(min_interior_weight(K), -1e-9);
  // Linear precision: the cotan Laplacian of a linear function vanishes at interior vertices,
  // on the intrinsic triangulation as on the original one (both are flat).
  const Eigen::VectorXd x = s.V.col(0) + 0.3 * s.V.col(1);
  const Eigen::VectorXd Kx = K * x;
  for (int j = 1; j + 1 < 15; ++j) {
    for (int i = 1; i + 1 < 15; ++i) EXPECT_NEAR(Kx(j * 15 + i), 0.0, 1e-9);
  }
}

TEST(IntrinsicDelaunay, DelaunayMeshIsUnchanged) {
  const Surface sphere = Icosphere(3);
  const IntrinsicTriangulation t = IntrinsicDelaunay(sphere);
  EXPECT_EQ(t.flips, 0);
  EXPECT_EQ(t.F, sphere.F);
  const Eigen::Matrix<double, 3, 2> p = IntrinsicLayout(t, 0);
  EXPECT_NEAR((p.row(2) - p.row(1)).norm(), t.L(0, 1), 1e-12);
  EXPECT_NEAR(p.row(2).norm(), t.L(0, 2), 1e-12);
  EXPECT_GT(p(2, 1), 0.0);
}

}  // namespace
}  // namespace symembed

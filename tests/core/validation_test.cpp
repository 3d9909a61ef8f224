// ValidateMesh on meshes built in code, one defect at a time, with exact expected counts.
#include "core/validation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "core/errors.h"
#include "core/primitives.h"

namespace symembed {
namespace {

Surface Make(const std::vector<Eigen::RowVector3d>& v, const std::vector<Eigen::RowVector3i>& f) {
  Surface s;
  s.V.resize(v.size(), 3);
  s.F.resize(f.size(), 3);
  for (size_t i = 0; i < v.size(); ++i) s.V.row(i) = v[i];
  for (size_t i = 0; i < f.size(); ++i) s.F.row(i) = f[i];
  return s;
}

Surface Tetrahedron(double shift = 0.0) {
  return Make({{shift, 0, 0}, {shift + 1, 0, 0}, {shift, 1, 0}, {shift, 0, 1}},
              {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}});
}

// Appends b to a (ids of b shifted).
Surface Join(const Surface& a, const Surface& b) {
  Surface s;
  s.V.resize(a.NumVertices() + b.NumVertices(), 3);
  s.V << a.V, b.V;
  s.F.resize(a.NumFaces() + b.NumFaces(), 3);
  s.F << a.F, (b.F.array() + a.NumVertices()).matrix();
  return s;
}

// Torus with n x m quads split into triangles, outward-oriented.
Surface Torus(int n, int m) {
  Surface s;
  s.V.resize(n * m, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      s.V.row(i * m + j) << (2 + std::cos(v)) * std::cos(u), (2 + std::cos(v)) * std::sin(u),
          std::sin(v);
    }
  }
  s.F.resize(2 * n * m, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const int a = i * m + j, b = ((i + 1) % n) * m + j, c = ((i + 1) % n) * m + (j + 1) % m,
                d = i * m + (j + 1) % m;
      s.F.row(2 * (i * m + j)) << a, b, c;
      s.F.row(2 * (i * m + j) + 1) << a, c, d;
    }
  }
  return s;
}

// Moebius strip: a band of n quads whose ends are glued with a half twist.
Surface Moebius(int n) {
  Surface s;
  s.V.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const double u = 2 * M_PI * i / n;
    for (int side = 0; side < 2; ++side) {
      const double w = side == 0 ? -0.3 : 0.3;
      s.V.row(2 * i + side) << (1 + w * std::cos(u / 2)) * std::cos(u),
          (1 + w * std::cos(u / 2)) * std::sin(u), w * std::sin(u / 2);
    }
  }
  s.F.resize(2 * n, 3);
  for (int i = 0; i < n; ++i) {
    const int a = 2 * i, b = 2 * i + 1;
    // The last quad meets the first with its sides swapped.
    const int c = i + 1 < n ? 2 * (i + 1) : 1, d = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    s.F.row(2 * i) << a, c, d;
    s.F.row(2 * i + 1) << a, d, b;
  }
  return s;
}

TEST(ValidateMesh, IcosphereIsCleanClosedGenusZero) {
  const Surface s = Icosphere(2);
  const MeshReport r = ValidateMesh(s, "sphere");
  EXPECT_TRUE(r.clean()) << r.ToString();
  EXPECT_EQ(r.num_vertices, 162);
  EXPECT_EQ(r.num_faces, 320);
  EXPECT_EQ(r.num_edges, 480);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.euler_characteristic, 2);
  EXPECT_TRUE(r.closed_manifold);
  EXPECT_EQ(r.genus, 0);
  EXPECT_NEAR(r.total_area, TotalArea(s), 1e-12);  // same sum, only summation order differs
  EXPECT_EQ(r.ToString(), "sphere: 162 vertices, 320 faces, area " +
                              [&] {
                                char b[32];
                                std::snprintf(b, sizeof(b), "%.6g", TotalArea(s));
                                return std::string(b);
                              }() +
                              ", closed, genus 0: clean\n");
}

TEST(ValidateMesh, TorusHasGenusOne) {
  const MeshReport r = ValidateMesh(Torus(12, 8), "torus");
  EXPECT_TRUE(r.clean()) << r.ToString();
  EXPECT_EQ(r.euler_characteristic, 0);
  EXPECT_EQ(r.genus, 1);
}

TEST(ValidateMesh, GridBoundaryIsOneLoop) {
  const MeshReport r = ValidateMesh(GridMesh(5, 4), "grid");
  EXPECT_EQ(r.boundary_edges, 2 * (4 + 3));
  EXPECT_EQ(r.boundary_loops, 1);
  EXPECT_FALSE(r.closed_manifold);
  EXPECT_EQ(r.genus, -1);
  ASSERT_EQ(r.issues.size(), 1u);
  EXPECT_EQ(r.issues[0], "boundary edges: 14 in 1 loop");
  EXPECT_NE(r.ToString().find(", open: 1 issue\n  boundary edges: 14 in 1 loop\n"),
            std::string::npos)
      << r.ToString();
}

TEST(ValidateMesh, OpenCylinderHasTwoBoundaryLoops) {
  const MeshReport r = ValidateMesh(Cylinder(10, 4), "cylinder");
  EXPECT_EQ(r.boundary_edges, 20);
  EXPECT_EQ(r.boundary_loops, 2);
  EXPECT_EQ(r.inconsistent_edges, 0);
}

TEST(ValidateMesh, ComponentsAreCounted) {
  const MeshReport r = ValidateMesh(Join(Tetrahedron(), Tetrahedron(5)), "two");
  EXPECT_EQ(r.components, 2);
  EXPECT_TRUE(r.closed_manifold);
  EXPECT_EQ(r.genus, 0);
  ASSERT_EQ(r.issues.size(), 1u);
  EXPECT_EQ(r.issues[0], "connected components: 2");
}

TEST(ValidateMesh, NonManifoldEdge) {
  // Three triangles on the edge 0-1.
  const Surface s = Make({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}},
                         {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const MeshReport r = ValidateMesh(s, "fin");
  EXPECT_EQ(r.non_manifold_edges, 1);
  EXPECT_EQ(r.non_manifold_vertices, 0);
  EXPECT_EQ(r.boundary_edges, 6);
  EXPECT_FALSE(r.closed_manifold);
  EXPECT_NE(r.ToString().find("non-manifold edges: 1 (e.g. edges 0-1)"), std::string::npos)
      << r.ToString();
}

TEST(ValidateMesh, NonManifoldVertexWhereTwoTetrahedraTouch) {
  // The second tetrahedron shares vertex 0 of the first: two fans around it.
  // Tetrahedron(-1)'s vertex 1 (id 5 after the join) sits at the origin, like vertex 0.
  Surface s = Join(Tetrahedron(), Tetrahedron(-1));
  for (int f = 4; f < 8; ++f) {
    for (int k = 0; k < 3; ++k) {
      if (s.F(f, k) == 5) s.F(f, k) = 0;
    }
  }
  const MeshReport r = ValidateMesh(s, "bowtie");
  EXPECT_EQ(r.non_manifold_vertices, 1);
  EXPECT_EQ(r.non_manifold_edges, 0);
  EXPECT_EQ(r.unreferenced_vertices, 1);  // the replaced vertex 5
  EXPECT_EQ(r.components, 1);
  EXPECT_FALSE(r.closed_manifold);
  EXPECT_NE(r.ToString().find("non-manifold vertices: 1 (e.g. vertices 0)"), std::string::npos);
}

TEST(ValidateMesh, DegenerateFaces) {
  Surface s = Icosphere(1);
  const int n = s.NumVertices();
  // A face on three collinear points (exactly zero area) and one repeating a vertex.
  s.V.conservativeResize(n + 3, 3);
  s.V.row(n) << 5, 5, 5;
  s.V.row(n + 1) << 6, 6, 6;
  s.V.row(n + 2) << 7.5, 7.5, 7.5;
  s.F.conservativeResize(s.NumFaces() + 2, 3);
  s.F.row(s.NumFaces() - 2) << n, n + 1, n + 2;
  s.F.row(s.NumFaces() - 1) << 0, 0, 1;
  const MeshReport r = ValidateMesh(s, "degenerate");
  EXPECT_EQ(r.degenerate_faces, 2);
  EXPECT_NE(r.ToString().find("degenerate (zero-area) faces: 2"), std::string::npos);
}

TEST(ValidateMesh, SliverAboveToleranceIsNotDegenerate) {
  // Height 1e-6 on a base of 1: twice the area / longest edge^2 = 1e-6 >> 1e-12.
  const Surface s = Make({{0, 0, 0}, {1, 0, 0}, {0.5, 1e-6, 0}}, {{0, 1, 2}});
  EXPECT_EQ(ValidateMesh(s, "sliver").degenerate_faces, 0);
  ValidationOptions options;
  options.degenerate_tolerance = 1e-5;
  EXPECT_EQ(ValidateMesh(s, "sliver", options).degenerate_faces, 1);
}

TEST(ValidateMesh, DuplicateFacesInEitherOrientation) {
  Surface s = Tetrahedron();
  s.F.conservativeResize(6, 3);
  s.F.row(4) = s.F.row(0);
  s.F.row(5) = s.F.row(1).reverse().eval();
  const MeshReport r = ValidateMesh(s, "dup");
  EXPECT_EQ(r.duplicate_faces, 2);
  EXPECT_EQ(r.non_manifold_edges, 5);  // every edge of faces 0 and 1 now has three faces
  EXPECT_NE(r.ToString().find("duplicate faces: 2 (e.g. face=earlier face 4=0, 5=1)"),
            std::string::npos)
      << r.ToString();
}

TEST(ValidateMesh, OneFlippedFace) {
  Surface s = Icosphere(2);
  std::swap(s.F(17, 1), s.F(17, 2));
  const MeshReport r = ValidateMesh(s, "flipped");
  SCOPED_TRACE(r.ToString());
  EXPECT_EQ(r.inconsistent_edges, 3);
  EXPECT_TRUE(r.orientable);
  EXPECT_EQ(r.flipped_faces, 1);
  EXPECT_TRUE(r.closed_manifold);  // topology is intact
  EXPECT_EQ(r.genus, 0);
  ASSERT_EQ(r.issues.size(), 1u);
  EXPECT_EQ(r.issues[0], "inconsistently oriented edges: 3 (1 faces appear flipped)");
}

TEST(ValidateMesh, FlippedHalfCountsTheSmallerSide) {
  Surface s = GridMesh(6, 6);
  // Flip the 10 faces of the first two rows of cells: 40 faces keep their orientation.
  for (int f = 0; f < 20; ++f) std::swap(s.F(f, 1), s.F(f, 2));
  const MeshReport r = ValidateMesh(s, "half");
  EXPECT_TRUE(r.orientable);
  EXPECT_EQ(r.flipped_faces, 20);
  EXPECT_EQ(r.inconsistent_edges, 5);  // the five interior edges between rows 2 and 3
}

TEST(ValidateMesh, MoebiusStripIsNotOrientable) {
  const MeshReport r = ValidateMesh(Moebius(12), "moebius");
  EXPECT_FALSE(r.orientable);
  EXPECT_EQ(r.boundary_loops, 1);  // a Moebius strip has one boundary curve
  EXPECT_EQ(r.non_manifold_edges, 0);
  EXPECT_NE(r.ToString().find("non-orientable"), std::string::npos);
}

TEST(ValidateMesh, NonFiniteCoordinatesAndUnreferencedVertices) {
  Surface s = Icosphere(1);
  s.V(3, 1) = std::numeric_limits<double>::quiet_NaN();
  s.V.conservativeResize(s.NumVertices() + 2, 3);
  s.V.bottomRows(2).setZero();
  s.V(s.NumVertices() - 1, 0) = std::numeric_limits<double>::infinity();
  const MeshReport r = ValidateMesh(s, "nan");
  EXPECT_EQ(r.nonfinite_vertices, 2);
  EXPECT_EQ(r.unreferenced_vertices, 2);
  EXPECT_TRUE(std::isfinite(r.total_area));  // faces on the NaN vertex are left out
  EXPECT_NE(r.ToString().find("vertices with NaN/Inf coordinates: 2 (e.g. vertices 3, 43)"),
            std::string::npos)
      << r.ToString();
  EXPECT_NE(r.ToString().find("unreferenced vertices: 2 (e.g. vertices 42, 43)"),
            std::string::npos);
}

TEST(ValidateMesh, OutOfRangeIdsAreCountedNotDereferenced) {
  Surface s = Tetrahedron();
  s.F.conservativeResize(6, 3);
  s.F.row(4) << 0, 1, 4;
  s.F.row(5) << -1, 0, 1;
  const MeshReport r = ValidateMesh(s, "ids");
  EXPECT_EQ(r.invalid_faces, 2);
  EXPECT_FALSE(r.closed_manifold);
  EXPECT_EQ(r.non_manifold_edges, 0);
}

TEST(ValidateMesh, EmptySurface) {
  const MeshReport r = ValidateMesh(Surface(), "empty");
  EXPECT_EQ(r.num_vertices, 0);
  EXPECT_EQ(r.components, 0);
  EXPECT_FALSE(r.closed_manifold);
}

TEST(ValidateMesh, OptionsAreChecked) {
  ValidationOptions options;
  std::string error;
  EXPECT_TRUE(options.IsValid(&error));
  options.degenerate_tolerance = -1;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("degenerate_tolerance"), std::string::npos);
  EXPECT_THROW(ValidateMesh(Tetrahedron(), "t", options), ConfigError);
}

}  // namespace
}  // namespace symembed

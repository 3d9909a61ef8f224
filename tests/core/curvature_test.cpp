#include "core/curvature.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/errors.h"
#include "core/primitives.h"

namespace symembed {
namespace {

// A height field z = f(x, y) on [-1, 1]^2 (faces counter-clockwise seen from +z, so normals
// point up) and the id of its centre vertex.
Surface HeightField(double a, double b, int n = 41) {
  Surface s = GridMesh(n, n, 2.0, 2.0);
  for (int v = 0; v < s.NumVertices(); ++v) {
    s.V(v, 0) -= 1.0;
    s.V(v, 1) -= 1.0;
    s.V(v, 2) = a * s.V(v, 0) * s.V(v, 0) + b * s.V(v, 1) * s.V(v, 1);
  }
  return s;
}

TEST(Curvature, SphereHasConstantMeanAndGaussianCurvature) {
  const double r = 3.0;
  const Surface sphere = Icosphere(4, r);
  for (int rings : {0, 2}) {
    const CurvatureFeatures c = ComputeCurvature(sphere, {rings, 0.0});
    // Level-4 icosphere: per-vertex discretisation error of cotan H and angle-defect K is a
    // few percent; the total angle defect is exactly 4 pi (Gauss-Bonnet).
    for (int v = 0; v < sphere.NumVertices(); ++v) {
      EXPECT_NEAR(c.mean(v), 1.0 / r, 0.03 / r);
      EXPECT_NEAR(c.gaussian(v), 1.0 / (r * r), 0.06 / (r * r));
      EXPECT_NEAR(c.shape_index(v), 1.0, 0.01);  // quadric fit: k1 - k2 = O(h^2) noise
      EXPECT_NEAR(c.normals.row(v).dot(sphere.V.row(v)) / r, 1.0, 1e-3);
      EXPECT_NEAR(c.normals.row(v).norm(), 1.0, 1e-12);
    }
  }
}

TEST(Curvature, CylinderIsARidge) {
  const double r = 1.5;
  const Surface cyl = Cylinder(64, 40, r, 6.0);
  const CurvatureFeatures c = ComputeCurvature(cyl, {1, 0.0});
  // Interior rows only: boundary vertices have one-sided stencils.
  for (int v = 3 * 64; v < 37 * 64; ++v) {
    EXPECT_NEAR(c.mean(v), 0.5 / r, 0.02 / r);
    EXPECT_NEAR(c.gaussian(v), 0.0, 1e-9);  // every interior angle sum is exactly 2 pi
    EXPECT_NEAR(c.k1(v), 1.0 / r, 0.04 / r);
    EXPECT_NEAR(c.k2(v), 0.0, 0.01 / r);  // the quadric fit sees the polygonal section
    EXPECT_NEAR(c.shape_index(v), 0.5, 0.01);
  }
}

TEST(Curvature, ShapeIndexSignsOnCapCupAndSaddle) {
  const int centre = 20 * 41 + 20;
  // z = -(x^2 + y^2) seen from +z is a cap, z = x^2 + y^2 a cup, z = x^2 - y^2 a saddle with
  // k1 = 2, k2 = -2 at the origin.
  const CurvatureFeatures cap = ComputeCurvature(HeightField(-1, -1));
  const CurvatureFeatures cup = ComputeCurvature(HeightField(1, 1));
  const CurvatureFeatures saddle = ComputeCurvature(HeightField(1, -1));
  EXPECT_GT(cap.mean(centre), 0.0);
  EXPECT_GT(cap.shape_index(centre), 0.9);
  EXPECT_LT(cup.mean(centre), 0.0);
  EXPECT_LT(cup.shape_index(centre), -0.9);
  EXPECT_NEAR(cap.gaussian(centre), 4.0, 0.4);  // K = 4 at the apex; 2-ring averaging lowers it
  EXPECT_LT(saddle.gaussian(centre), -3.0);
  EXPECT_NEAR(saddle.shape_index(centre), 0.0, 0.05);
  EXPECT_NEAR(saddle.k1(centre), 2.0, 0.2);
  EXPECT_NEAR(saddle.k2(centre), -2.0, 0.2);
}

TEST(Curvature, RadiusSmoothingAndValidation) {
  const Surface sphere = Icosphere(3, 1.0);
  const CurvatureFeatures c = ComputeCurvature(sphere, {0, 0.1});
  for (int v = 0; v < sphere.NumVertices(); ++v) EXPECT_NEAR(c.mean(v), 1.0, 0.03);
  EXPECT_THROW(ComputeCurvature(sphere, {-1, 0.0}), ConfigError);
  EXPECT_THROW(ComputeCurvature(sphere, {0, -1.0}), ConfigError);
}

TEST(Curvature, IsolatedVerticesGetZeros) {
  Surface s = Icosphere(1);
  s.V.conservativeResize(s.NumVertices() + 1, 3);
  s.V.row(s.NumVertices() - 1) << 9, 9, 9;
  const CurvatureFeatures c = ComputeCurvature(s);
  const int last = s.NumVertices() - 1;
  EXPECT_EQ(c.mean(last), 0.0);
  EXPECT_EQ(c.shape_index(last), 0.0);
  EXPECT_EQ(c.normals.row(last).norm(), 0.0);
}

}  // namespace
}  // namespace symembed

// Small meshes built in code, with known geometry, for tests, benchmarks and examples.
#pragma once

#include "core/mesh.h"

namespace symembed {

// Flat grid on [0, width] x [0, height] in the z = 0 plane, nx x ny vertices, each cell split
// into two triangles (alternating diagonals so distances have no preferred direction).
Surface GridMesh(int nx, int ny, double width = 1.0, double height = 1.0);

// Icosphere of the given radius: the icosahedron subdivided `levels` times (10 * 4^levels + 2
// vertices), vertices projected to the sphere.
Surface Icosphere(int levels, double radius = 1.0);

// Open cylinder of the given radius and height along z: n_around x n_along vertices.
Surface Cylinder(int n_around, int n_along, double radius = 1.0, double height = 1.0);

// Closed axis-aligned box [-sx/2, sx/2] x [-sy/2, sy/2] x [-sz/2, sz/2], each face an n x n grid.
Surface BoxMesh(int n, double sx = 1.0, double sy = 1.0, double sz = 1.0);

}  // namespace symembed

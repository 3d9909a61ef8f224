// Intrinsic Delaunay triangulation by edge flips.
//
// The vertices and the surface's metric are unchanged; only the connectivity changes, and
// edges become geodesic segments on the input surface whose lengths are computed by laying out
// pairs of triangles in the plane. Operators built on it (cotan Laplacian, gradients) have
// non-negative cotan weights, so the Laplacian satisfies a discrete maximum principle even on
// meshes with many obtuse triangles, where the extrinsic cotan Laplacian does not.
//
// [Bobenko & Springborn 2007] A discrete Laplace-Beltrami operator for simplicial surfaces;
// [Fisher et al. 2007] An algorithm for the construction of intrinsic Delaunay triangulations
// with applications to digital geometry processing;
// [Sharp, Soliman & Crane 2019] Navigating intrinsic triangulations.
#pragma once

#include <Eigen/Core>
#include <Eigen/Sparse>

#include "core/mesh.h"

namespace symembed {

struct IntrinsicTriangulation {
  Eigen::MatrixX3i F;  // #F x 3 vertex ids, counter-clockwise like the input
  Eigen::MatrixX3d L;  // #F x 3: L(f, k) = length of the edge from F(f, k) to F(f, (k+1) % 3)
  int flips = 0;       // edge flips performed
};

// The intrinsic triangulation of `surface` itself (no flips).
IntrinsicTriangulation IntrinsicFromSurface(const Surface& surface);

// Flips non-Delaunay interior edges (sum of the opposite angles > pi) until none is left or
// max_flips is reached (0 = 100 * #F). Boundary, non-manifold and inconsistently oriented
// edges are never flipped.
IntrinsicTriangulation IntrinsicDelaunay(const Surface& surface, int max_flips = 0);

// Per-face areas (#F) from the edge lengths.
Eigen::VectorXd IntrinsicFaceAreas(const IntrinsicTriangulation& t);

// Cotangent stiffness matrix (num_vertices x num_vertices), as core/laplacian.h CotanStiffness.
Eigen::SparseMatrix<double> IntrinsicCotanStiffness(const IntrinsicTriangulation& t,
                                                    int num_vertices);

// Lumped mass matrix diagonal: one third of the incident face areas per vertex.
Eigen::VectorXd IntrinsicVertexAreas(const IntrinsicTriangulation& t, int num_vertices);

// 2D layout of face f: corner 0 at the origin, corner 1 on +x, corner 2 in the upper half
// plane. Rows are the corners.
Eigen::Matrix<double, 3, 2> IntrinsicLayout(const IntrinsicTriangulation& t, int f);

}  // namespace symembed

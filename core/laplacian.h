// Discrete Laplace-Beltrami operators on triangle meshes.
//
// [Pinkall & Polthier 1993] Computing discrete minimal surfaces and their conjugates;
// [Meyer et al. 2003] Discrete differential-geometry operators for triangulated 2-manifolds.
#pragma once

#include <Eigen/Sparse>

#include "core/mesh.h"

namespace symembed {

// Cotangent stiffness matrix L (#V x #V), symmetric positive semi-definite:
// (L u)_i = 1/2 sum_j (cot a_ij + cot b_ij) (u_i - u_j). Boundary edges get one cotangent
// (natural Neumann condition). Rows of unreferenced vertices are empty.
Eigen::SparseMatrix<double> CotanStiffness(const Surface& surface);

enum class MassType { kLumped, kConsistent };

// Mass matrix M (#V x #V): lumped = diagonal, one third of the incident triangle areas per
// vertex; consistent = the piecewise-linear FEM mass matrix (area/6 diagonal, area/12 off).
Eigen::SparseMatrix<double> MassMatrix(const Surface& surface, MassType type = MassType::kLumped);

// Per-vertex lumped areas (diagonal of the lumped mass matrix), #V.
Eigen::VectorXd VertexAreas(const Surface& surface);

// Unit vertex normals, #V x 3: area-weighted sums of the face normals (outward for
// counter-clockwise faces seen from outside); zero rows for vertices in no face.
Eigen::MatrixX3d VertexNormals(const Surface& surface);
// The same for positions V (#V x 3) other than the surface's own, e.g. an embedding of its
// vertices: the normals of the embedded surface.
Eigen::MatrixX3d VertexNormals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F);

}  // namespace symembed

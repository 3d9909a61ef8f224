// The mesh type of the project and its Eigen views.
//
// TriMesh is an OpenMesh array-kernel triangle mesh with double-precision points; it is used for
// I/O, validation, repair, subdivision and decimation. Numerical algorithms work on the Eigen
// views (libigl notation):
//   V  #V by 3 vertex positions
//   F  #F by 3 vertex indices per triangle, counter-clockwise seen from outside
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>  // cross products on rows of V
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <string>

namespace symembed {

struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  using Color = OpenMesh::Vec3uc;
  VertexAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
  FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
  EdgeAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};

using TriMesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

// A surface as the numerical stages see it.
struct Surface {
  Eigen::MatrixX3d V;  // #V x 3 positions
  Eigen::MatrixX3i F;  // #F x 3 triangle vertex ids (0-based)

  int NumVertices() const { return static_cast<int>(V.rows()); }
  int NumFaces() const { return static_cast<int>(F.rows()); }
};

// Eigen views of an OpenMesh mesh (deleted elements must have been garbage-collected).
Eigen::MatrixX3d VertexMatrix(const TriMesh& mesh);
Eigen::MatrixX3i FaceMatrix(const TriMesh& mesh);
Surface ToSurface(const TriMesh& mesh);

// Builds an OpenMesh mesh from V, F. Faces OpenMesh cannot add (complex edges, non-manifold
// vertices) are skipped; their count is returned through *skipped_faces when given.
TriMesh FromSurface(const Surface& surface, int* skipped_faces = nullptr);

// Per-face areas (#F) and total area.
Eigen::VectorXd FaceAreas(const Surface& surface);
double TotalArea(const Surface& surface);

// Mean edge length over all face edges (each interior edge counted twice).
double MeanEdgeLength(const Surface& surface);

}  // namespace symembed

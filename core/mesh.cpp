#include "core/mesh.h"

#include <Eigen/Geometry>
#include <vector>

#include "core/errors.h"

namespace symembed {

Eigen::MatrixX3d VertexMatrix(const TriMesh& mesh) {
  Eigen::MatrixX3d V(mesh.n_vertices(), 3);
  for (auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    V.row(vh.idx()) << p[0], p[1], p[2];
  }
  return V;
}

Eigen::MatrixX3i FaceMatrix(const TriMesh& mesh) {
  Eigen::MatrixX3i F(mesh.n_faces(), 3);
  for (auto fh : mesh.faces()) {
    int k = 0;
    for (auto vh : mesh.fv_range(fh)) {
      SYMEMBED_CHECK(k < 3, "face " << fh.idx() << " is not a triangle");
      F(fh.idx(), k++) = vh.idx();
    }
  }
  return F;
}

Surface ToSurface(const TriMesh& mesh) { return Surface{VertexMatrix(mesh), FaceMatrix(mesh)}; }

TriMesh FromSurface(const Surface& surface, int* skipped_faces) {
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> handles;
  handles.reserve(surface.V.rows());
  for (int i = 0; i < surface.V.rows(); ++i) {
    handles.push_back(
        mesh.add_vertex(TriMesh::Point(surface.V(i, 0), surface.V(i, 1), surface.V(i, 2))));
  }
  int skipped = 0;
  for (int f = 0; f < surface.F.rows(); ++f) {
    auto fh = mesh.add_face(handles[surface.F(f, 0)], handles[surface.F(f, 1)],
                            handles[surface.F(f, 2)]);
    if (!fh.is_valid()) ++skipped;
  }
  if (skipped_faces) *skipped_faces = skipped;
  return mesh;
}

Eigen::VectorXd FaceAreas(const Surface& s) {
  Eigen::VectorXd a(s.F.rows());
  for (int f = 0; f < s.F.rows(); ++f) {
    const Eigen::Vector3d e1 = s.V.row(s.F(f, 1)) - s.V.row(s.F(f, 0));
    const Eigen::Vector3d e2 = s.V.row(s.F(f, 2)) - s.V.row(s.F(f, 0));
    a(f) = 0.5 * e1.cross(e2).norm();
  }
  return a;
}

double TotalArea(const Surface& s) { return FaceAreas(s).sum(); }

double MeanEdgeLength(const Surface& s) {
  if (s.F.rows() == 0) return 0.0;
  double sum = 0.0;
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      sum += (s.V.row(s.F(f, k)) - s.V.row(s.F(f, (k + 1) % 3))).norm();
    }
  }
  return sum / (3.0 * s.F.rows());
}

}  // namespace symembed

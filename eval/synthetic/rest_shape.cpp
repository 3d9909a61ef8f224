#include "eval/synthetic/rest_shape.h"

#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/CatmullClarkT.hh>
#include <array>
#include <cmath>
#include <unordered_map>

#include "core/errors.h"

namespace symembed {

namespace {

struct PolyTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<PolyTraits>;

// Catmull-Clark on the control quads with the given per-point values (3 channels). The
// subdivision's topology does not depend on the values, so calls with the same quads produce
// the same vertex order and faces: positions and weight channels stay aligned.
PolyMesh Subdivide(const std::vector<std::array<int, 4>>& quads,
                   const std::vector<Eigen::Vector3d>& values, int levels) {
  PolyMesh mesh;
  std::vector<PolyMesh::VertexHandle> vh;
  vh.reserve(values.size());
  for (const auto& p : values) vh.push_back(mesh.add_vertex(PolyMesh::Point(p.x(), p.y(), p.z())));
  for (const auto& q : quads) {
    const auto fh = mesh.add_face({vh[q[0]], vh[q[1]], vh[q[2]], vh[q[3]]});
    SYMEMBED_CHECK(fh.is_valid(), "box model face could not be added (non-manifold model)");
  }
  OpenMesh::Subdivider::Uniform::CatmullClarkT<PolyMesh, double> subdivider;
  subdivider.attach(mesh);
  subdivider(static_cast<size_t>(levels));
  subdivider.detach();
  return mesh;
}

struct CellHash {
  size_t operator()(const std::array<long long, 3>& k) const {
    return static_cast<size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
  }
};

// Triangle split of quad (a, b, c, d): the shorter diagonal; ties broken by the vertex with the
// largest (|x|, y, z), a rule that is invariant under x -> -x, so mirrored quads split alike.
bool SplitAlongAC(const Eigen::MatrixX3d& V, const std::array<int, 4>& q) {
  const double ac = (V.row(q[0]) - V.row(q[2])).squaredNorm();
  const double bd = (V.row(q[1]) - V.row(q[3])).squaredNorm();
  if (ac < bd * (1.0 - 1e-9)) return true;
  if (bd < ac * (1.0 - 1e-9)) return false;
  int best = 0;
  auto key = [&](int k) {
    return std::array<double, 3>{std::abs(V(q[k], 0)), V(q[k], 1), V(q[k], 2)};
  };
  for (int k = 1; k < 4; ++k) {
    if (key(k) > key(best)) best = k;
  }
  return best == 0 || best == 2;
}

}  // namespace

std::vector<int> MirrorMap(const Eigen::MatrixX3d& V, double tolerance) {
  const double cell = std::max(tolerance * 4.0, 1e-12);
  auto key_of = [&](double x, double y, double z) {
    return std::array<long long, 3>{std::llround(x / cell), std::llround(y / cell),
                                    std::llround(z / cell)};
  };
  std::unordered_map<std::array<long long, 3>, std::vector<int>, CellHash> grid;
  for (int i = 0; i < V.rows(); ++i) grid[key_of(V(i, 0), V(i, 1), V(i, 2))].push_back(i);
  std::vector<int> mirror(V.rows(), -1);
  for (int i = 0; i < V.rows(); ++i) {
    const Eigen::RowVector3d m(-V(i, 0), V(i, 1), V(i, 2));
    const auto k = key_of(m.x(), m.y(), m.z());
    int found = -1, count = 0;
    for (long long dx = -1; dx <= 1; ++dx) {
      for (long long dy = -1; dy <= 1; ++dy) {
        for (long long dz = -1; dz <= 1; ++dz) {
          auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (int j : it->second) {
            if ((V.row(j) - m).norm() <= tolerance) {
              found = j;
              ++count;
            }
          }
        }
      }
    }
    if (count == 1) mirror[i] = found;
  }
  return mirror;
}

void ChooseResolution(FigureKind kind, int target_vertices, int* rings_per_segment, int* levels) {
  double best = 1e300;
  for (int k = 1; k <= 4; ++k) {
    for (int s = 1; s <= 12; ++s) {
      const double n = std::pow(4.0, k) * ControlQuadCount(kind, s) + 2.0;
      // One level leaves the figure faceted: use it only when it is much closer to the target.
      const double cost = std::abs(std::log(n / target_vertices)) + (k == 1 ? 0.05 : 0.0);
      if (cost < best) {
        best = cost;
        *rings_per_segment = s;
        *levels = k;
      }
    }
  }
}

RestFigure MakeRestFigure(FigureKind kind, int target_vertices) {
  SYMEMBED_CHECK(target_vertices >= 100, "target_vertices must be >= 100");
  RestFigure rest;
  ChooseResolution(kind, target_vertices, &rest.rings_per_segment, &rest.levels);
  rest.figure = BuildFigure(kind, rest.rings_per_segment);
  const ControlMesh& control = rest.figure.control;
  const int num_bones = static_cast<int>(rest.figure.bones.size());

  const PolyMesh mesh = Subdivide(control.quads, control.points, rest.levels);
  const int n = static_cast<int>(mesh.n_vertices());
  Eigen::MatrixX3d V(n, 3);
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    V.row(v.idx()) << p[0], p[1], p[2];
  }
  std::vector<std::array<int, 4>> quads;
  quads.reserve(mesh.n_faces());
  for (auto f : mesh.faces()) {
    std::array<int, 4> q{};
    int k = 0;
    for (auto v : mesh.fv_range(f)) {
      SYMEMBED_CHECK(k < 4, "Catmull-Clark produced a face that is not a quad");
      q[k++] = v.idx();
    }
    SYMEMBED_CHECK(k == 4, "Catmull-Clark produced a face that is not a quad");
    quads.push_back(q);
  }

  // Skinning weights, three bones per subdivision pass.
  rest.weights = Eigen::MatrixXd::Zero(n, num_bones);
  for (int b0 = 0; b0 < num_bones; b0 += 3) {
    std::vector<Eigen::Vector3d> channels(control.points.size(), Eigen::Vector3d::Zero());
    for (size_t i = 0; i < channels.size(); ++i) {
      for (int c = 0; c < 3 && b0 + c < num_bones; ++c) channels[i][c] = control.weights(i, b0 + c);
    }
    const PolyMesh wmesh = Subdivide(control.quads, channels, rest.levels);
    SYMEMBED_CHECK(static_cast<int>(wmesh.n_vertices()) == n, "weight subdivision diverged");
    for (auto v : wmesh.vertices()) {
      const auto& w = wmesh.point(v);
      for (int c = 0; c < 3 && b0 + c < num_bones; ++c) rest.weights(v.idx(), b0 + c) = w[c];
    }
  }

  // Mirror map (the model is symmetric up to rounding), then exact symmetry by averaging.
  rest.mirror = MirrorMap(V, 1e-9);
  for (int i = 0; i < n; ++i) {
    SYMEMBED_CHECK(rest.mirror[i] >= 0 && rest.mirror[rest.mirror[i]] == i,
                   "subdivided figure is not mirror-symmetric at vertex " << i);
  }
  std::vector<int> bone_mirror(num_bones);
  for (int b = 0; b < num_bones; ++b) bone_mirror[b] = rest.figure.bones[b].mirror;
  for (int i = 0; i < n; ++i) {
    const int m = rest.mirror[i];
    if (m == i) {
      V(i, 0) = 0.0;
    } else if (i < m) {
      const double x = 0.5 * (V(i, 0) - V(m, 0)), y = 0.5 * (V(i, 1) + V(m, 1)),
                   z = 0.5 * (V(i, 2) + V(m, 2));
      V.row(i) << x, y, z;
      V.row(m) << -x, y, z;
    }
    if (i <= m) {
      Eigen::VectorXd w = rest.weights.row(i).transpose();
      for (int b = 0; b < num_bones; ++b) w[b] = 0.5 * (w[b] + rest.weights(m, bone_mirror[b]));
      for (int b = 0; b < num_bones; ++b) {
        rest.weights(i, b) = w[b];
        rest.weights(m, bone_mirror[b]) = w[b];
      }
    }
  }

  rest.surface.V = V;
  rest.surface.F.resize(2 * static_cast<int>(quads.size()), 3);
  for (size_t f = 0; f < quads.size(); ++f) {
    const auto& q = quads[f];
    if (SplitAlongAC(V, q)) {
      rest.surface.F.row(2 * f) << q[0], q[1], q[2];
      rest.surface.F.row(2 * f + 1) << q[0], q[2], q[3];
    } else {
      rest.surface.F.row(2 * f) << q[0], q[1], q[3];
      rest.surface.F.row(2 * f + 1) << q[1], q[2], q[3];
    }
  }
  return rest;
}

}  // namespace symembed

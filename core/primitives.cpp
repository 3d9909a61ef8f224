#include "core/primitives.h"

#include <cmath>
#include <map>
#include <tuple>
#include <utility>
#include <vector>

#include "core/errors.h"

namespace symembed {

Surface GridMesh(int nx, int ny, double width, double height) {
  SYMEMBED_CHECK(nx >= 2 && ny >= 2, "grid needs at least 2 x 2 vertices");
  Surface s;
  s.V.resize(nx * ny, 3);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      s.V.row(j * nx + i) << width * i / (nx - 1), height * j / (ny - 1), 0.0;
    }
  }
  s.F.resize(2 * (nx - 1) * (ny - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < ny; ++j) {
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx, d = c + 1;
      if ((i + j) % 2 == 0) {
        s.F.row(f++) << a, b, d;
        s.F.row(f++) << a, d, c;
      } else {
        s.F.row(f++) << a, b, c;
        s.F.row(f++) << b, d, c;
      }
    }
  }
  return s;
}

Surface Icosphere(int levels, double radius) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> V = {{-1, t, 0}, {1, t, 0},   {-1, -t, 0}, {1, -t, 0},
                                    {0, -1, t}, {0, 1, t},   {0, -1, -t}, {0, 1, -t},
                                    {t, 0, -1}, {t, 0, 1},   {-t, 0, -1}, {-t, 0, 1}};
  std::vector<Eigen::Vector3i> F = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& v : V) v.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      auto key = std::minmax(a, b);
      auto it = midpoint.find(key);
      if (it != midpoint.end()) return it->second;
      V.push_back((V[a] + V[b]).normalized());
      midpoint[key] = static_cast<int>(V.size()) - 1;
      return static_cast<int>(V.size()) - 1;
    };
    std::vector<Eigen::Vector3i> next;
    for (const auto& f : F) {
      const int ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    F = std::move(next);
  }
  Surface s;
  s.V.resize(V.size(), 3);
  for (size_t i = 0; i < V.size(); ++i) s.V.row(i) = radius * V[i].transpose();
  s.F.resize(F.size(), 3);
  for (size_t i = 0; i < F.size(); ++i) s.F.row(i) = F[i].transpose();
  return s;
}

Surface Cylinder(int n_around, int n_along, double radius, double height) {
  SYMEMBED_CHECK(n_around >= 3 && n_along >= 2, "cylinder needs n_around >= 3, n_along >= 2");
  Surface s;
  s.V.resize(n_around * n_along, 3);
  for (int j = 0; j < n_along; ++j) {
    for (int i = 0; i < n_around; ++i) {
      const double a = 2.0 * M_PI * i / n_around;
      s.V.row(j * n_around + i) << radius * std::cos(a), radius * std::sin(a),
          height * j / (n_along - 1);
    }
  }
  s.F.resize(2 * n_around * (n_along - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n_along; ++j) {
    for (int i = 0; i < n_around; ++i) {
      const int a = j * n_around + i, b = j * n_around + (i + 1) % n_around;
      const int c = a + n_around, d = b + n_around;
      s.F.row(f++) << a, b, d;
      s.F.row(f++) << a, d, c;
    }
  }
  return s;
}

Surface BoxMesh(int n, double sx, double sy, double sz) {
  SYMEMBED_CHECK(n >= 1, "box needs n >= 1");
  std::vector<Eigen::Vector3d> V;
  std::vector<Eigen::Vector3i> F;
  std::map<std::tuple<long, long, long>, int> index;  // shared corner/edge vertices
  auto vertex = [&](const Eigen::Vector3d& p) {
    auto key = std::make_tuple(std::lround(p.x() * 2 * n), std::lround(p.y() * 2 * n),
                               std::lround(p.z() * 2 * n));
    auto it = index.find(key);
    if (it != index.end()) return it->second;
    V.push_back(p);
    return index[key] = static_cast<int>(V.size()) - 1;
  };
  // Each face: origin corner o and two axes u, v with u x v pointing outwards.
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {-1, 1}) {
      Eigen::Vector3d normal = Eigen::Vector3d::Zero();
      normal[axis] = sign;
      Eigen::Vector3d u = Eigen::Vector3d::Zero(), v = Eigen::Vector3d::Zero();
      u[(axis + 1) % 3] = 1;
      v[(axis + 2) % 3] = 1;
      if (sign < 0) std::swap(u, v);
      const Eigen::Vector3d o = 0.5 * normal - 0.5 * u - 0.5 * v;
      std::vector<int> ids((n + 1) * (n + 1));
      for (int j = 0; j <= n; ++j) {
        for (int i = 0; i <= n; ++i) ids[j * (n + 1) + i] = vertex(o + u * i / n + v * j / n);
      }
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const int a = ids[j * (n + 1) + i], b = ids[j * (n + 1) + i + 1];
          const int c = ids[(j + 1) * (n + 1) + i], d = ids[(j + 1) * (n + 1) + i + 1];
          F.push_back({a, b, d});
          F.push_back({a, d, c});
        }
      }
    }
  }
  Surface s;
  s.V.resize(V.size(), 3);
  for (size_t i = 0; i < V.size(); ++i) {
    s.V.row(i) << V[i].x() * sx, V[i].y() * sy, V[i].z() * sz;
  }
  s.F.resize(F.size(), 3);
  for (size_t i = 0; i < F.size(); ++i) s.F.row(i) = F[i].transpose();
  return s;
}

}  // namespace symembed

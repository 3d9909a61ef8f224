#include "core/curvature.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>

#include "core/errors.h"
#include "core/laplacian.h"
#include "core/mesh_graph.h"

namespace symembed {

bool CurvatureOptions::IsValid(std::string* error) const {
  if (smoothing_rings < 0) {
    if (error) *error = "smoothing_rings must be >= 0, got " + std::to_string(smoothing_rings);
    return false;
  }
  if (!(smoothing_radius >= 0.0) || !std::isfinite(smoothing_radius)) {
    if (error) *error = "smoothing_radius must be finite and >= 0";
    return false;
  }
  return true;
}

namespace {

// Mixed Voronoi area of every vertex [Meyer et al. 2003, Fig. 4]: the Voronoi region inside
// non-obtuse triangles, half (at the obtuse corner) or a quarter of obtuse ones. Sums to the
// total area and, unlike the barycentric area, matches the cotan Laplacian's stencil.
Eigen::VectorXd MixedAreas(const Surface& s) {
  Eigen::VectorXd a = Eigen::VectorXd::Zero(s.NumVertices());
  for (int f = 0; f < s.NumFaces(); ++f) {
    const Eigen::Vector3d p[3] = {s.V.row(s.F(f, 0)), s.V.row(s.F(f, 1)), s.V.row(s.F(f, 2))};
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    if (area <= 0.0) continue;
    double cot[3];
    int obtuse = -1;
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], w = p[(k + 2) % 3] - p[k];
      cot[k] = u.dot(w) / (2.0 * area);
      if (u.dot(w) < 0.0) obtuse = k;
    }
    for (int k = 0; k < 3; ++k) {
      const int i = (k + 1) % 3, j = (k + 2) % 3;
      if (obtuse < 0) {
        a(s.F(f, k)) += ((p[i] - p[k]).squaredNorm() * cot[j] +
                         (p[j] - p[k]).squaredNorm() * cot[i]) / 8.0;
      } else {
        a(s.F(f, k)) += obtuse == k ? area / 2.0 : area / 4.0;
      }
    }
  }
  return a;
}

// The neighbourhood of every vertex: its k-ring (breadth-first) or, when radius > 0, the
// vertices within edge-graph distance `radius`. Includes the vertex itself, first.
class Neighbourhoods {
 public:
  Neighbourhoods(const Surface& s, int rings, double radius)
      : graph_(BuildMeshGraph(s)), rings_(rings), radius_(radius),
        mark_(s.NumVertices(), -1) {}

  const std::vector<int>& Of(int v) {
    ids_.clear();
    if (radius_ > 0.0) {
      DijkstraBall(graph_, v, radius_, &ball_, &ws_);
      for (const auto& entry : ball_) ids_.push_back(entry.first);
      return ids_;
    }
    mark_[v] = v;  // mark_[w] == v: w is already in v's neighbourhood
    ids_.push_back(v);
    size_t begin = 0;
    for (int ring = 0; ring < rings_ && begin < ids_.size(); ++ring) {
      const size_t end = ids_.size();
      for (size_t i = begin; i < end; ++i) {
        const int u = ids_[i];
        for (int k = graph_.offsets[u]; k < graph_.offsets[u + 1]; ++k) {
          const int w = graph_.neighbors[k];
          if (mark_[w] != v) {
            mark_[w] = v;
            ids_.push_back(w);
          }
        }
      }
      begin = end;
    }
    return ids_;
  }

 private:
  MeshGraph graph_;
  int rings_;
  double radius_;
  std::vector<int> mark_, ids_;
  std::vector<std::pair<int, double>> ball_;
  DijkstraWorkspace<double> ws_;
};

// Principal curvatures (k1 >= k2, sign convention of the header) from a least-squares fit of
// the height function z = a x^2 + b xy + c y^2 + d x + e y over the neighbourhood, in the
// tangent frame of the normal n [Cazals & Pouget 2005] Estimating differential quantities
// using polynomial fitting of osculating jets. Returns false when the fit is underdetermined.
bool FitPrincipalCurvatures(const Surface& s, int v, const Eigen::Vector3d& n,
                            const std::vector<int>& ids, double* k1, double* k2) {
  if (ids.size() < 6 || n.squaredNorm() == 0.0) return false;
  const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  Eigen::Matrix<double, 5, 5> AtA = Eigen::Matrix<double, 5, 5>::Zero();
  Eigen::Matrix<double, 5, 1> Atz = Eigen::Matrix<double, 5, 1>::Zero();
  double scale = 0.0;
  for (size_t i = 1; i < ids.size(); ++i) scale += (s.V.row(ids[i]) - s.V.row(v)).norm();
  scale /= static_cast<double>(ids.size() - 1);
  if (scale <= 0.0) return false;
  // Coordinates are divided by the mean neighbour distance to keep the system well scaled.
  for (size_t i = 1; i < ids.size(); ++i) {
    const Eigen::Vector3d p = (s.V.row(ids[i]) - s.V.row(v)).transpose() / scale;
    const double x = p.dot(t1), y = p.dot(t2), z = p.dot(n);
    Eigen::Matrix<double, 5, 1> row;
    row << x * x, x * y, y * y, x, y;
    AtA += row * row.transpose();
    Atz += row * z;
  }
  const Eigen::LDLT<Eigen::Matrix<double, 5, 5>> ldlt(AtA);
  if (ldlt.info() != Eigen::Success || ldlt.rcond() < 1e-10) return false;
  const Eigen::Matrix<double, 5, 1> c = ldlt.solve(Atz);
  // First and second fundamental forms of the graph at the origin; the shape operator is
  // I^-1 II. The minus sign makes curvature positive where the surface bends away from n.
  const double d = c(3), e = c(4), w = std::sqrt(1.0 + d * d + e * e);
  const double E = 1 + d * d, F = d * e, G = 1 + e * e;
  const double L = 2 * c(0) / w, M = c(1) / w, N = 2 * c(2) / w;
  const double det = E * G - F * F;
  const double H = -(E * N - 2 * F * M + G * L) / (2 * det) / scale;
  const double K = (L * N - M * M) / det / (scale * scale);
  const double root = std::sqrt(std::max(H * H - K, 0.0));
  *k1 = H + root;
  *k2 = H - root;
  return true;
}

}  // namespace

CurvatureFeatures ComputeCurvature(const Surface& s, const CurvatureOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("curvature: " + error);
  const int n = s.NumVertices();
  CurvatureFeatures c;
  c.normals = VertexNormals(s);
  Eigen::VectorXd angle_sum = Eigen::VectorXd::Zero(n);
  for (int f = 0; f < s.NumFaces(); ++f) {
    const Eigen::Vector3d p[3] = {s.V.row(s.F(f, 0)), s.V.row(s.F(f, 1)), s.V.row(s.F(f, 2))};
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d u = p[(k + 1) % 3] - p[k], w = p[(k + 2) % 3] - p[k];
      angle_sum(s.F(f, k)) += std::atan2(u.cross(w).norm(), u.dot(w));
    }
  }
  // Boundary vertices: endpoints of edges used by exactly one face.
  std::vector<char> boundary(n, 0);
  {
    std::vector<std::pair<int, int>> edges;
    edges.reserve(3 * s.NumFaces());
    for (int f = 0; f < s.NumFaces(); ++f) {
      for (int k = 0; k < 3; ++k) edges.push_back(std::minmax(s.F(f, k), s.F(f, (k + 1) % 3)));
    }
    std::sort(edges.begin(), edges.end());
    for (size_t i = 0; i < edges.size();) {
      size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      if (j - i == 1) boundary[edges[i].first] = boundary[edges[i].second] = 1;
      i = j;
    }
  }
  const Eigen::VectorXd area = MixedAreas(s);
  const Eigen::MatrixX3d LV = CotanStiffness(s) * s.V;
  Eigen::MatrixXd HK = Eigen::MatrixXd::Zero(n, 2);
  for (int v = 0; v < n; ++v) {
    if (area(v) <= 0.0) continue;
    HK(v, 0) = LV.row(v).dot(c.normals.row(v)) / (2.0 * area(v));
    HK(v, 1) = ((boundary[v] ? M_PI : 2.0 * M_PI) - angle_sum(v)) / area(v);
  }
  // H and K are averaged over each neighbourhood (area-weighted); k1 and k2 are fitted over
  // the same neighbourhood, at least the 2-ring so that the quadric fit is determined.
  const bool by_radius = options.smoothing_radius > 0.0;
  const double radius = options.smoothing_radius * std::sqrt(area.sum());
  Neighbourhoods smoothing(s, options.smoothing_rings, radius);
  Neighbourhoods fitting(s, std::max(options.smoothing_rings, 2), radius);
  c.mean = Eigen::VectorXd::Zero(n);
  c.gaussian = Eigen::VectorXd::Zero(n);
  c.k1 = Eigen::VectorXd::Zero(n);
  c.k2 = Eigen::VectorXd::Zero(n);
  c.shape_index = Eigen::VectorXd::Zero(n);
  for (int v = 0; v < n; ++v) {
    if (area(v) <= 0.0) continue;
    double weight = 0.0;
    for (int w : smoothing.Of(v)) {
      c.mean(v) += area(w) * HK(w, 0);
      c.gaussian(v) += area(w) * HK(w, 1);
      weight += area(w);
    }
    c.mean(v) /= weight;
    c.gaussian(v) /= weight;
    const std::vector<int>& ids = by_radius ? smoothing.Of(v) : fitting.Of(v);
    double k1, k2;
    if (!FitPrincipalCurvatures(s, v, c.normals.row(v).transpose(), ids, &k1, &k2)) {
      // Too few neighbours for a fit: fall back to the discrete H and K.
      const double H = c.mean(v), root = std::sqrt(std::max(H * H - c.gaussian(v), 0.0));
      k1 = H + root;
      k2 = H - root;
    }
    c.k1(v) = k1;
    c.k2(v) = k2;
    c.shape_index(v) = (2.0 / M_PI) * std::atan2(k1 + k2, k1 - k2);
  }
  return c;
}

}  // namespace symembed

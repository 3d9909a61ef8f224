#include "eval/synthetic/variations.h"

#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModAspectRatioT.hh>
#include <OpenMesh/Tools/Decimater/ModBaseT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Subdivider/Uniform/LoopT.hh>
#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>

#include "core/errors.h"
#include "core/knn.h"
#include "core/laplacian.h"
#include "core/mesh_graph.h"
#include "eval/synthetic/posing.h"
#include "eval/synthetic/random.h"

namespace symembed {

namespace {

// Collapse priority: squared edge length, stretched by `anisotropy` along `direction`, times a
// per-vertex factor of the removed vertex.
template <class MeshT>
class ModJitteredLengthT : public OpenMesh::Decimater::ModBaseT<MeshT> {
 public:
  DECIMATING_MODULE(ModJitteredLengthT, MeshT, JitteredLength);

  explicit ModJitteredLengthT(MeshT& mesh) : Base(mesh, false) {}

  void set_factors(const std::vector<double>* factors) { factors_ = factors; }
  void set_stretch(double anisotropy, const Eigen::Vector3d& direction) {
    extra_ = anisotropy * anisotropy - 1.0;
    direction_ = direction;
  }

  float collapse_priority(const CollapseInfo& ci) override {
    const auto e = ci.p0 - ci.p1;
    const double along = e[0] * direction_.x() + e[1] * direction_.y() + e[2] * direction_.z();
    return static_cast<float>((e.sqrnorm() + extra_ * along * along) * (*factors_)[ci.v0.idx()]);
  }

 private:
  const std::vector<double>* factors_ = nullptr;
  double extra_ = 0.0;  // anisotropy^2 - 1
  Eigen::Vector3d direction_ = Eigen::Vector3d::UnitX();
};

// Drops faces listed as false in keep_face and vertices no kept face uses; renumbers.
TrackedSurface KeepFaces(const TrackedSurface& shape, const std::vector<bool>& keep_face) {
  const Surface& s = shape.surface;
  std::vector<int> new_id(s.V.rows(), -1);
  int nf = 0;
  for (int f = 0; f < s.F.rows(); ++f) {
    if (!keep_face[f]) continue;
    ++nf;
    for (int k = 0; k < 3; ++k) new_id[s.F(f, k)] = 0;
  }
  TrackedSurface out;
  int nv = 0;
  for (int v = 0; v < s.V.rows(); ++v) {
    if (new_id[v] < 0) continue;
    new_id[v] = nv++;
    out.rest_ids.push_back(shape.rest_ids[v]);
  }
  out.surface.V.resize(nv, 3);
  for (int v = 0; v < s.V.rows(); ++v) {
    if (new_id[v] >= 0) out.surface.V.row(new_id[v]) = s.V.row(v);
  }
  out.surface.F.resize(nf, 3);
  for (int f = 0, g = 0; f < s.F.rows(); ++f) {
    if (!keep_face[f]) continue;
    for (int k = 0; k < 3; ++k) out.surface.F(g, k) = new_id[s.F(f, k)];
    ++g;
  }
  return out;
}

// Bones apart in the skeleton (the length of the path between them through their parents).
int SkeletonDistance(const std::vector<Bone>& bones, int a, int b) {
  std::vector<int> depth_a(bones.size(), -1);
  for (int x = a, d = 0; x >= 0; x = bones[x].parent, ++d) depth_a[x] = d;
  for (int x = b, d = 0; x >= 0; x = bones[x].parent, ++d) {
    if (depth_a[x] >= 0) return depth_a[x] + d;
  }
  return static_cast<int>(bones.size());
}

// Whether a short circuit between two parts is topological noise rather than their joint.
bool MayGlue(const std::vector<Bone>& bones, int a, int b) {
  const int d = SkeletonDistance(bones, a, b);
  const bool siblings = bones[a].parent >= 0 && bones[a].parent == bones[b].parent;
  return d >= 3 || (d == 2 && !siblings);
}

struct FacePair {
  double distance;
  int f, g;
};

// Facing pairs of faces of parts that may be glued, each face with its nearest facing faces of
// every other such part, sorted by centroid distance.
std::vector<FacePair> GlueCandidates(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
                                     const std::vector<Bone>& bones) {
  const Surface& s = shape.surface;
  const int nf = s.NumFaces();
  const int nb = static_cast<int>(bones.size());
  Eigen::MatrixXd centroids(nf, 3);
  Eigen::MatrixX3d normals(nf, 3);
  std::vector<int> part(nf);
  for (int f = 0; f < nf; ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    centroids.row(f) = (a + b + c) / 3.0;
    normals.row(f) = (b - a).cross(c - a).normalized();
    Eigen::VectorXd w = Eigen::VectorXd::Zero(nb);
    for (int k = 0; k < 3; ++k) w += weights.row(shape.rest_ids[s.F(f, k)]).transpose();
    w.maxCoeff(&part[f]);
  }
  std::vector<std::vector<int>> faces_of(nb);
  for (int f = 0; f < nf; ++f) faces_of[part[f]].push_back(f);
  std::vector<FacePair> out;
  constexpr int kNearest = 2;
  for (int pb = 0; pb < nb; ++pb) {
    if (faces_of[pb].empty()) continue;
    Eigen::MatrixXd points(faces_of[pb].size(), 3);
    for (size_t i = 0; i < faces_of[pb].size(); ++i) points.row(i) = centroids.row(faces_of[pb][i]);
    const KnnIndex index(points);
    const int k = std::min<int>(kNearest, static_cast<int>(faces_of[pb].size()));
    for (int pa = 0; pa < pb; ++pa) {
      if (faces_of[pa].empty() || !MayGlue(bones, pa, pb)) continue;
      Eigen::MatrixXd queries(faces_of[pa].size(), 3);
      for (size_t i = 0; i < faces_of[pa].size(); ++i)
        queries.row(i) = centroids.row(faces_of[pa][i]);
      Eigen::MatrixXi ids;
      Eigen::MatrixXd distances;
      index.Query(queries, k, &ids, &distances, 1);
      for (size_t i = 0; i < faces_of[pa].size(); ++i) {
        const int f = faces_of[pa][i];
        for (int j = 0; j < k; ++j) {
          const int g = faces_of[pb][ids(i, j)];
          const Eigen::Vector3d d = (centroids.row(g) - centroids.row(f)).transpose();
          if (d.dot(normals.row(f).transpose()) > 0.0 && d.dot(normals.row(g).transpose()) < 0.0) {
            out.push_back({distances(i, j), f, g});
          }
        }
      }
    }
  }
  std::sort(out.begin(), out.end(), [](const FacePair& x, const FacePair& y) {
    return std::tie(x.distance, x.f, x.g) < std::tie(y.distance, y.f, y.g);
  });
  return out;
}

// The candidates (sorted by distance) whose faces are at least kShortCircuit times their
// centroids' distance apart along the surface's edges, so that gluing them short-circuits the
// surface: at most max_count, and none farther than the first one plus extra_reach. The
// distance along the edges is bounded from below through kLandmarks farthest-point landmarks
// l (|d(l, a) - d(l, b)| <= d(a, b)); a pair counts when that bound reaches the factor.
constexpr double kShortCircuit = 3.0;
constexpr int kLandmarks = 48;

std::vector<FacePair> ShortCircuits(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
                                    const std::vector<Bone>& bones, int max_count,
                                    double extra_reach) {
  const Surface& s = shape.surface;
  const int nv = s.NumVertices();
  const MeshGraph graph = BuildMeshGraph(s);
  DijkstraWorkspace<double> workspace;
  std::vector<std::vector<double>> landmark_dist;
  std::vector<double> nearest(nv, std::numeric_limits<double>::infinity());
  for (int l = 0, v = 0; l < std::min(kLandmarks, nv); ++l) {
    landmark_dist.emplace_back(nv);
    Dijkstra(graph, v, landmark_dist.back().data(), &workspace);
    for (int u = 0; u < nv; ++u) nearest[u] = std::min(nearest[u], landmark_dist.back()[u]);
    v = static_cast<int>(std::max_element(nearest.begin(), nearest.end()) - nearest.begin());
  }
  auto lower_bound = [&](int a, int b) {
    double bound = 0.0;
    for (const auto& d : landmark_dist) bound = std::max(bound, std::abs(d[a] - d[b]));
    return bound;
  };
  std::vector<FacePair> out;
  for (const FacePair& c : GlueCandidates(shape, weights, bones)) {
    if (static_cast<int>(out.size()) == max_count) break;
    if (!out.empty() && c.distance > out[0].distance + extra_reach) break;
    if (lower_bound(s.F(c.f, 0), s.F(c.g, 0)) >= kShortCircuit * c.distance) out.push_back(c);
  }
  return out;
}

// Keeps the faces of the connected component (through shared vertices) with the most faces.
TrackedSurface KeepLargestComponent(const TrackedSurface& shape) {
  const Surface& s = shape.surface;
  std::vector<int> parent(s.NumVertices());
  for (int v = 0; v < s.NumVertices(); ++v) parent[v] = v;
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 1; k < 3; ++k) parent[find(s.F(f, k))] = find(s.F(f, 0));
  }
  std::vector<int> faces(s.NumVertices(), 0);
  for (int f = 0; f < s.NumFaces(); ++f) ++faces[find(s.F(f, 0))];
  const int largest =
      static_cast<int>(std::max_element(faces.begin(), faces.end()) - faces.begin());
  std::vector<bool> keep(s.NumFaces());
  for (int f = 0; f < s.NumFaces(); ++f) keep[f] = find(s.F(f, 0)) == largest;
  return KeepFaces(shape, keep);
}

}  // namespace

double GlueGap(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
               const std::vector<Bone>& bones) {
  const std::vector<FacePair> found = ShortCircuits(shape, weights, bones, 1, 0.0);
  return found.empty() ? std::numeric_limits<double>::infinity() : found[0].distance;
}

TrackedSurface PullIntoContact(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
                               const std::vector<Bone>& bones, double* gap) {
  const std::vector<FacePair> found = ShortCircuits(shape, weights, bones, 1, 0.0);
  if (gap) *gap = found.empty() ? std::numeric_limits<double>::infinity() : found[0].distance;
  if (found.empty()) return shape;
  const Surface& s = shape.surface;
  const FacePair& c = found[0];
  Eigen::Vector3d cf = Eigen::Vector3d::Zero(), cg = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) {
    cf += s.V.row(s.F(c.f, k)).transpose() / 3.0;
    cg += s.V.row(s.F(c.g, k)).transpose() / 3.0;
  }
  const Eigen::Vector3d half = 0.5 * (cg - cf);
  const double radius = std::max(2.0 * c.distance, 3.0 * MeanEdgeLength(s));
  const MeshGraph graph = BuildMeshGraph(s);
  DijkstraWorkspace<double> workspace;
  std::vector<std::pair<int, double>> ball;
  TrackedSurface out = shape;
  // Each side moves half the gap towards the other, fading out smoothly over `radius`.
  for (const auto& [face, sign] : {std::make_pair(c.f, 1.0), std::make_pair(c.g, -1.0)}) {
    DijkstraBall(graph, s.F(face, 0), radius, &ball, &workspace);
    for (const auto& [v, d] : ball) {
      const double t = 1.0 - (d / radius) * (d / radius);
      out.surface.V.row(v) += (sign * t * t) * half.transpose();
    }
  }
  return out;
}

TrackedSurface GlueParts(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
                         const std::vector<Bone>& bones, int max_bridges, double* gap) {
  SYMEMBED_CHECK(max_bridges >= 1, "glue needs at least one bridge");
  const Surface& s = shape.surface;
  // Candidates share vertices, so more are gathered than bridges are built.
  const std::vector<FacePair> candidates =
      ShortCircuits(shape, weights, bones, 64 * max_bridges, 2.0 * MeanEdgeLength(s));
  if (gap)
    *gap = candidates.empty() ? std::numeric_limits<double>::infinity() : candidates[0].distance;
  if (candidates.empty()) return shape;
  std::vector<char> used(s.NumVertices(), 0);
  std::vector<bool> keep(s.NumFaces(), true);
  std::vector<Eigen::Vector3i> tubes;
  int bridges = 0;
  for (const FacePair& c : candidates) {
    if (bridges == max_bridges) break;
    bool free = true;
    for (int k = 0; k < 3; ++k) free = free && !used[s.F(c.f, k)] && !used[s.F(c.g, k)];
    if (!free) continue;
    // t1 = (a, b, c) and t2 = (d, e, f) face each other, so a tube that keeps the orientation
    // pairs t1's vertices with t2's in reverse order; of the three such pairings, the shortest.
    const int t1[3] = {s.F(c.f, 0), s.F(c.f, 1), s.F(c.f, 2)};
    const int t2[3] = {s.F(c.g, 0), s.F(c.g, 1), s.F(c.g, 2)};
    int best = 0;
    double best_length = std::numeric_limits<double>::infinity();
    for (int r = 0; r < 3; ++r) {
      double length = 0.0;
      for (int k = 0; k < 3; ++k)
        length += (s.V.row(t1[k]) - s.V.row(t2[(r + 3 - k) % 3])).squaredNorm();
      if (length < best_length) {
        best_length = length;
        best = r;
      }
    }
    auto partner = [&](int k) { return t2[(best + 3 - k) % 3]; };
    for (int k = 0; k < 3; ++k) {
      // The quad (p, q, q', p') over t1's edge p -> q.
      const int p = t1[k], q = t1[(k + 1) % 3];
      tubes.emplace_back(p, q, partner((k + 1) % 3));
      tubes.emplace_back(p, partner((k + 1) % 3), partner(k));
    }
    for (int k = 0; k < 3; ++k) used[t1[k]] = used[t2[k]] = 1;
    keep[c.f] = keep[c.g] = false;
    ++bridges;
  }
  TrackedSurface out;
  out.rest_ids = shape.rest_ids;
  out.surface.V = s.V;
  int nf = 0;
  for (int f = 0; f < s.NumFaces(); ++f) nf += keep[f];
  out.surface.F.resize(nf + static_cast<int>(tubes.size()), 3);
  int row = 0;
  for (int f = 0; f < s.NumFaces(); ++f) {
    if (keep[f]) out.surface.F.row(row++) = s.F.row(f);
  }
  for (const Eigen::Vector3i& t : tubes) out.surface.F.row(row++) = t.transpose();
  return out;
}

TrackedSurface CutHole(const TrackedSurface& shape, int center, double radius) {
  SYMEMBED_CHECK(center >= 0 && center < shape.surface.NumVertices(), "hole centre out of range");
  const MeshGraph graph = BuildMeshGraph(shape.surface);
  std::vector<std::pair<int, double>> ball;
  DijkstraWorkspace<double> workspace;
  DijkstraBall(graph, center, radius, &ball, &workspace);
  std::vector<bool> inside(shape.surface.NumVertices(), false);
  for (const auto& [v, d] : ball) inside[v] = true;
  std::vector<bool> keep(shape.surface.NumFaces(), true);
  for (int f = 0; f < shape.surface.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (inside[shape.surface.F(f, k)]) keep[f] = false;
    }
  }
  return KeepLargestComponent(KeepFaces(shape, keep));
}

TrackedSurface CutByPlane(const TrackedSurface& shape, const Eigen::Vector3d& normal,
                          double removed) {
  const Surface& s = shape.surface;
  std::vector<double> height(s.NumVertices());
  for (int v = 0; v < s.NumVertices(); ++v) height[v] = s.V.row(v).dot(normal);
  std::vector<double> sorted = height;
  const size_t at = std::min(sorted.size() - 1, static_cast<size_t>(removed * sorted.size()));
  std::nth_element(sorted.begin(), sorted.begin() + at, sorted.end());
  const double offset = sorted[at];
  std::vector<bool> keep(s.NumFaces(), true);
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (height[s.F(f, k)] < offset) keep[f] = false;
    }
  }
  return KeepLargestComponent(KeepFaces(shape, keep));
}

TrackedSurface CutPart(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
                       const std::vector<Bone>& bones, int bone) {
  const int nb = static_cast<int>(bones.size());
  std::vector<bool> in_part(nb, false);
  for (int b = 0; b < nb; ++b) {
    // Parents precede children, so one pass marks the whole subtree.
    in_part[b] = b == bone || (bones[b].parent >= 0 && in_part[bones[b].parent]);
  }
  const Surface& s = shape.surface;
  std::vector<bool> removed(s.V.rows(), false);
  for (int v = 0; v < s.V.rows(); ++v) {
    double w = 0.0;
    for (int b = 0; b < nb; ++b) {
      if (in_part[b]) w += weights(shape.rest_ids[v], b);
    }
    removed[v] = w > 0.5;
  }
  std::vector<bool> keep(s.F.rows(), true);
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (removed[s.F(f, k)]) keep[f] = false;
    }
  }
  return KeepFaces(shape, keep);
}

TrackedSurface Remesh(const TrackedSurface& shape, int target_vertices, uint32_t seed,
                      double anisotropy, const Eigen::Vector3d& direction) {
  SYMEMBED_CHECK(target_vertices >= 4, "remesh target must be >= 4 vertices");
  SYMEMBED_CHECK(anisotropy >= 1.0, "remesh anisotropy must be >= 1");
  SYMEMBED_CHECK(std::abs(direction.norm() - 1.0) < 1e-9, "remesh direction must be a unit vector");
  int skipped = 0;
  TriMesh mesh = FromSurface(shape.surface, &skipped);
  SYMEMBED_CHECK(skipped == 0, "remesh input is not a manifold mesh");
  OpenMesh::VPropHandleT<int> rest_id;
  mesh.add_property(rest_id);
  for (auto v : mesh.vertices()) mesh.property(rest_id, v) = shape.rest_ids[v.idx()];
  mesh.update_face_normals();

  std::vector<double> factors(mesh.n_vertices());
  SynthRandom random(seed);
  for (double& f : factors) f = random.Uniform(0.5, 1.5);

  using Decimater = OpenMesh::Decimater::DecimaterT<TriMesh>;
  Decimater decimater(mesh);
  typename ModJitteredLengthT<TriMesh>::Handle length;
  typename OpenMesh::Decimater::ModNormalFlippingT<TriMesh>::Handle flipping;
  decimater.add(length);
  decimater.add(flipping);
  decimater.module(length).set_factors(&factors);
  decimater.module(length).set_stretch(anisotropy, direction);
  decimater.module(flipping).set_max_normal_deviation(45.0);
  // Elongated triangles are the point of an anisotropic remeshing, slivers are not: a collapse
  // that leaves a triangle thinner than the anisotropy asks for is refused.
  typename OpenMesh::Decimater::ModAspectRatioT<TriMesh>::Handle aspect;
  if (anisotropy > 1.0) {
    decimater.add(aspect);
    decimater.module(aspect).set_aspect_ratio(static_cast<float>(3.0 * anisotropy));
  }
  SYMEMBED_CHECK(decimater.initialize(), "decimater did not initialize");
  decimater.decimate_to(static_cast<size_t>(target_vertices));
  mesh.garbage_collection();

  TrackedSurface out;
  out.surface = ToSurface(mesh);
  out.rest_ids.resize(mesh.n_vertices());
  for (auto v : mesh.vertices()) out.rest_ids[v.idx()] = mesh.property(rest_id, v);
  return out;
}

TrackedSurface Subdivide(const TrackedSurface& shape, int levels) {
  SYMEMBED_CHECK(levels >= 0, "subdivision levels must be >= 0");
  if (levels == 0) return shape;
  int skipped = 0;
  TriMesh mesh = FromSurface(shape.surface, &skipped);
  SYMEMBED_CHECK(skipped == 0, "subdivision input is not a manifold mesh");
  OpenMesh::Subdivider::Uniform::LoopT<TriMesh> loop;
  loop.attach(mesh);
  loop(static_cast<size_t>(levels));
  loop.detach();
  // LoopT only adds vertices (splitting edges), so the old ones keep their handles.
  TrackedSurface out;
  out.surface = ToSurface(mesh);
  out.rest_ids.assign(mesh.n_vertices(), -1);
  std::copy(shape.rest_ids.begin(), shape.rest_ids.end(), out.rest_ids.begin());
  return out;
}

void AddNormalNoise(Surface* surface, double amplitude, uint32_t seed) {
  const Eigen::MatrixX3d N = VertexNormals(*surface);
  const double scale = amplitude * MeanEdgeLength(*surface);
  SynthRandom random(seed);
  for (int v = 0; v < surface->V.rows(); ++v) {
    surface->V.row(v) += scale * random.Uniform(-1.0, 1.0) * N.row(v);
  }
}

}  // namespace symembed

#include "eval/synthetic/synthetic.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <queue>
#include <set>

#include "core/errors.h"
#include "core/laplacian.h"
#include "core/validation.h"
#include "eval/datasets/pairs_vts.h"
#include "eval/synthetic/posing.h"
#include "eval/synthetic/random.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

namespace fs = std::filesystem;

void ExpectClosedGenusZero(const Surface& s, const std::string& what) {
  const MeshReport report = ValidateMesh(s, what);
  EXPECT_TRUE(report.clean()) << report.ToString();
  EXPECT_TRUE(report.closed_manifold) << report.ToString();
  EXPECT_EQ(report.components, 1) << report.ToString();
  EXPECT_EQ(report.genus, 0) << report.ToString();
}

double SignedVolume(const Surface& s) {
  double v = 0.0;
  for (int f = 0; f < s.NumFaces(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

// Shortest edge-graph paths from `source` to every vertex.
std::vector<double> Dijkstra(const Surface& s, int source) {
  std::vector<std::vector<std::pair<int, double>>> adj(s.NumVertices());
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      const double w = (s.V.row(a) - s.V.row(b)).norm();
      adj[a].push_back({b, w});
      adj[b].push_back({a, w});
    }
  }
  std::vector<double> d(s.NumVertices(), 1e300);
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  d[source] = 0.0;
  queue.push({0.0, source});
  while (!queue.empty()) {
    const auto [du, u] = queue.top();
    queue.pop();
    if (du > d[u]) continue;
    for (const auto& [w, len] : adj[u]) {
      if (du + len < d[w]) queue.push({d[w] = du + len, w});
    }
  }
  return d;
}

// The mean relative change |d_b - d_a| / d_a of edge-graph distances from 8 sources to every
// vertex of a and b (same vertex ids), each shape's distances divided by its scale; vertices
// nearer than 0.05 scale units to the source, where the relative change is ill-conditioned, are
// left out.
double MeanRelativeDistanceChange(const Surface& a, const Surface& b, double scale_a = 1.0,
                                  double scale_b = 1.0) {
  double sum = 0.0;
  int count = 0;
  for (int k = 0; k < 8; ++k) {
    const int source = (k * 7919) % a.NumVertices();
    const auto da = Dijkstra(a, source), db = Dijkstra(b, source);
    for (size_t v = 0; v < da.size(); ++v) {
      if (da[v] / scale_a < 0.05) continue;
      sum += std::abs(db[v] / scale_b - da[v] / scale_a) / (da[v] / scale_a);
      ++count;
    }
  }
  return sum / count;
}

SynthOptions Options(FigureKind kind, int poses, int vertices) {
  SynthOptions o;
  o.kinds = {kind};
  o.poses = poses;
  o.vertices = vertices;
  return o;
}

class SyntheticKinds : public ::testing::TestWithParam<FigureKind> {};

TEST_P(SyntheticKinds, RestShapeIsClosedManifoldOrientedGenusZero) {
  const RestFigure rest = MakeRestFigure(GetParam(), 2000);
  ExpectClosedGenusZero(rest.surface, FigureKindName(GetParam()));
  EXPECT_GT(SignedVolume(rest.surface), 0.0) << "normals must point outwards";
  for (int i = 0; i < rest.weights.rows(); ++i) {
    // Subdivision stencils are affine; the sum of weights is 1 up to rounding.
    ASSERT_NEAR(rest.weights.row(i).sum(), 1.0, 1e-12) << i;
    ASSERT_GE(rest.weights.row(i).minCoeff(), -1e-12) << i;
  }
}

TEST_P(SyntheticKinds, RestShapeIsExactlyMirrorSymmetric) {
  const RestFigure rest = MakeRestFigure(GetParam(), 2000);
  const Surface& s = rest.surface;
  ASSERT_EQ(static_cast<int>(rest.mirror.size()), s.NumVertices());
  int on_plane = 0;
  for (int i = 0; i < s.NumVertices(); ++i) {
    const int m = rest.mirror[i];
    ASSERT_GE(m, 0);
    ASSERT_EQ(rest.mirror[m], i);  // an involution, hence a bijection
    // Exact: bit-identical mirrored coordinates.
    ASSERT_EQ(s.V(m, 0), -s.V(i, 0));
    ASSERT_EQ(s.V(m, 1), s.V(i, 1));
    ASSERT_EQ(s.V(m, 2), s.V(i, 2));
    if (m == i) ++on_plane;
  }
  EXPECT_GT(on_plane, 0);
  // The mirror map is a mesh automorphism: every face maps to a face (orientation reversed).
  std::set<std::array<int, 3>> faces;
  auto canonical = [](int a, int b, int c) {
    std::array<int, 3> f = {a, b, c};
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    return f;
  };
  for (int f = 0; f < s.NumFaces(); ++f) faces.insert(canonical(s.F(f, 0), s.F(f, 1), s.F(f, 2)));
  for (int f = 0; f < s.NumFaces(); ++f) {
    const auto& m = rest.mirror;
    ASSERT_TRUE(faces.count(canonical(m[s.F(f, 0)], m[s.F(f, 2)], m[s.F(f, 1)]))) << f;
  }
  // The figure is centred on the plane and has parts on both sides.
  EXPECT_LT(s.V.col(0).minCoeff(), -0.1);
  EXPECT_EQ(s.V.col(0).maxCoeff(), -s.V.col(0).minCoeff());
}

// Front and back differ (faces, feet, chest; the quadruped's head and tail), so that a flip
// scorer has something to find: the rest shape reflected front-to-back about its mean z is far
// from itself. Mean distance to the nearest vertex at 1.5k vertices: measured 13 mm (humanoid)
// and 24 mm (quadruped); a front-back symmetric box model gives 0, since its subdivided
// vertices map onto each other.
TEST_P(SyntheticKinds, RestShapeHasADistinctFront) {
  const Surface s = MakeRestFigure(GetParam(), 1500).surface;
  const double mean_z = s.V.col(2).mean();
  double sum = 0.0;
  for (int i = 0; i < s.NumVertices(); ++i) {
    const Eigen::RowVector3d r(s.V(i, 0), s.V(i, 1), 2 * mean_z - s.V(i, 2));
    sum += std::sqrt((s.V.rowwise() - r).rowwise().squaredNorm().minCoeff());
  }
  const double mean = sum / s.NumVertices();
  RecordProperty("front_back_distance", std::to_string(mean));
  EXPECT_GT(mean, 0.004);
}

TEST_P(SyntheticKinds, VertexCountIsNearTheTarget) {
  for (int target : {1000, 5000, 20000}) {
    const RestFigure rest = MakeRestFigure(GetParam(), target);
    // Catmull-Clark multiplies the face count by 4 per level; the ring count per segment fills
    // in between, so the nearest reachable count is within 35 % at these targets.
    EXPECT_NEAR(rest.surface.NumVertices(), target, 0.35 * target) << target;
  }
}

TEST_P(SyntheticKinds, PosesKeepTheIdentityGroundTruth) {
  const SynthClass c = GenerateClass(GetParam(), Options(GetParam(), 4, 1500));
  const RestFigure& rest = c.rest;
  ASSERT_EQ(c.shapes.size(), 4u);
  for (const SynthShape& shape : c.shapes) {
    const Surface& s = shape.shape.surface;
    ASSERT_EQ(s.NumVertices(), rest.surface.NumVertices());
    EXPECT_TRUE(s.F == rest.surface.F) << shape.name;  // same vertex ids, same faces
    for (int i = 0; i < s.NumVertices(); ++i) ASSERT_EQ(shape.shape.rest_ids[i], i);
    ExpectClosedGenusZero(s, shape.name);
    EXPECT_GT(SignedVolume(s), 0.0);
    // Posed: it moved.
    EXPECT_GT((s.V - rest.surface.V).rowwise().norm().maxCoeff(), 0.05) << shape.name;
  }
  // The identity pose reproduces the rest shape (weights sum to 1; 1e-12 m is rounding).
  const Eigen::MatrixX3d V = SkinVertices(rest, RestPose(static_cast<int>(rest.figure.bones.size())));
  EXPECT_LT((V - rest.surface.V).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(c.pairs.size(), 6u);
}

// Linear blend skinning bends the surface only near joints, so geodesics change little.
// Measured (seed 1, 1.5k vertices): the mean relative change of edge-graph distances from 8
// sources to all vertices is 1.3-2.5 % per pose; 6 % leaves room for other seeds and sizes.
// Non-isometric scaling (R = 0.3) changes them 2-4 times as much (required: 1.5 times).
TEST_P(SyntheticKinds, GeodesicsAreNearlyPreservedWithoutNonisometricScaling) {
  SynthOptions o = Options(GetParam(), 4, 1500);
  const SynthClass iso = GenerateClass(GetParam(), o);
  o.nonisometric = 0.3;
  const SynthClass scaled = GenerateClass(GetParam(), o);
  const Surface& rest = iso.rest.surface;
  for (size_t p = 0; p < iso.shapes.size(); ++p) {
    const double iso_change = MeanRelativeDistanceChange(rest, iso.shapes[p].shape.surface);
    const double scaled_change =
        MeanRelativeDistanceChange(rest, scaled.shapes[p].shape.surface);
    EXPECT_LT(iso_change, 0.06) << iso.shapes[p].name;
    EXPECT_GT(scaled_change, 1.5 * iso_change) << iso.shapes[p].name;
    RecordProperty(iso.shapes[p].name + "_iso", std::to_string(iso_change));
    RecordProperty(iso.shapes[p].name + "_nonisometric", std::to_string(scaled_change));
  }
}

// Distal limb parts (forearms, hands, shins, feet; lower legs and paws; head) never enter the
// torso's box in the default angle ranges (checked over 40 poses).
TEST_P(SyntheticKinds, LimbsStayOutOfTheTorso) {
  const SynthClass c = GenerateClass(GetParam(), Options(GetParam(), 40, 1500));
  const RestFigure& rest = c.rest;
  const auto& bones = rest.figure.bones;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (int i = 0; i < rest.figure.control.weights.rows(); ++i) {
    if (rest.figure.control.weights(i, 0) < 1.0) continue;
    lo = lo.cwiseMin(rest.figure.control.points[i]);
    hi = hi.cwiseMax(rest.figure.control.points[i]);
  }
  std::vector<bool> distal(bones.size(), false);
  for (size_t b = 1; b < bones.size(); ++b) {
    // Not attached to the torso, and not the second tail bone (a tail may curl over the back).
    distal[b] = bones[b].parent != 0 && bones[b].name != "tail_tip";
  }
  for (const SynthShape& shape : c.shapes) {
    int inside = 0, checked = 0;
    for (int v = 0; v < shape.shape.surface.NumVertices(); ++v) {
      int dominant = 0;
      rest.weights.row(v).maxCoeff(&dominant);
      if (!distal[dominant]) continue;
      ++checked;
      const Eigen::Vector3d p = shape.shape.surface.V.row(v);
      if ((p.array() > lo.array()).all() && (p.array() < hi.array()).all()) ++inside;
    }
    EXPECT_EQ(inside, 0) << shape.name;
    EXPECT_GT(checked, shape.shape.surface.NumVertices() / 5) << shape.name;
  }
}

TEST_P(SyntheticKinds, RemeshedPosesKeepExactGroundTruth) {
  SynthOptions o = Options(GetParam(), 3, 2000);
  const SynthClass full = GenerateClass(GetParam(), o);
  o.remesh = 700;
  const SynthClass remeshed = GenerateClass(GetParam(), o);
  std::vector<std::set<int>> kept;
  for (size_t p = 0; p < remeshed.shapes.size(); ++p) {
    const TrackedSurface& r = remeshed.shapes[p].shape;
    const Surface& f = full.shapes[p].shape.surface;
    EXPECT_EQ(r.surface.NumVertices(), 700);
    ExpectClosedGenusZero(r.surface, remeshed.shapes[p].name);
    std::set<int> ids(r.rest_ids.begin(), r.rest_ids.end());
    EXPECT_EQ(ids.size(), r.rest_ids.size()) << "rest ids are distinct";
    for (int v = 0; v < r.surface.NumVertices(); ++v) {
      // Halfedge collapses never move the surviving vertex: positions are bit-identical.
      ASSERT_TRUE(r.surface.V.row(v) == f.V.row(r.rest_ids[v])) << v;
    }
    kept.push_back(ids);
  }
  // Independent per pose: different poses keep different vertex subsets.
  EXPECT_NE(kept[0], kept[1]);
}

// An anisotropic remeshing keeps the edges along its direction short and those across it long,
// with the ground truth exact and the surface closed; anisotropy 1 is the isotropic remeshing.
TEST_P(SyntheticKinds, AnisotropicRemeshingShortensTheEdgesAlongItsDirection) {
  SynthOptions o = Options(GetParam(), 1, 2000);
  const TrackedSurface posed = GenerateClass(GetParam(), o).shapes[0].shape;
  for (const Eigen::Vector3d& d :
       {Eigen::Vector3d::UnitY().eval(), Eigen::Vector3d::UnitZ().eval()}) {
    const TrackedSurface iso = Remesh(posed, 700, 5);
    const TrackedSurface aniso = Remesh(posed, 700, 5, 4.0, d);
    EXPECT_EQ(aniso.surface.NumVertices(), 700);
    ExpectClosedGenusZero(aniso.surface, "anisotropic remeshing");
    for (int v = 0; v < aniso.surface.NumVertices(); ++v) {
      ASSERT_TRUE(aniso.surface.V.row(v) == posed.surface.V.row(aniso.rest_ids[v])) << v;
    }
    const double iso_ratio = testing::EdgeExtentRatio(iso.surface, d);
    const double aniso_ratio = testing::EdgeExtentRatio(aniso.surface, d);
    // Along the figures' long axes, 2,000 -> 700 vertices: 0.6-0.8 of the isotropic ratio.
    EXPECT_LT(aniso_ratio, 0.9 * iso_ratio) << iso_ratio << " " << aniso_ratio;
  }
  // Through the generator: one random direction per pose, so the poses' meshings differ in kind.
  o.poses = 2;
  o.remesh = 700;
  o.remesh_anisotropy = 4.0;
  const SynthClass c = GenerateClass(GetParam(), o);
  EXPECT_NE(c.shapes[0].note.find("anisotropy 4"), std::string::npos) << c.shapes[0].note;
  EXPECT_EQ(c.shapes[1].shape.surface.NumVertices(), 700);
  EXPECT_NE(SynthOptionsText(o).find("remesh_anisotropy: 4"), std::string::npos);
  o.remesh_anisotropy = 1.0;
  EXPECT_EQ(SynthOptionsText(o).find("remesh_anisotropy"), std::string::npos);
}

// Loop subdivision: four triangles per triangle, a vertex per edge, the old vertices moved by a
// fraction of an edge and keeping their ids, the new ones without a rest vertex; the surface
// stays closed and its area nearly the same (Loop's smoothing moves it by a fraction of an edge).
TEST_P(SyntheticKinds, SubdivisionAddsAVertexPerEdgeAndKeepsTheOldIds) {
  const TrackedSurface posed =
      GenerateClass(GetParam(), Options(GetParam(), 1, 1000)).shapes[0].shape;
  const Surface& s = posed.surface;
  const int nv = s.NumVertices(), nf = s.NumFaces();
  const int ne = nv + nf - 2;  // Euler characteristic 2
  const TrackedSurface once = Subdivide(posed, 1);
  EXPECT_EQ(once.surface.NumVertices(), nv + ne);
  EXPECT_EQ(once.surface.NumFaces(), 4 * nf);
  ExpectClosedGenusZero(once.surface, "subdivided");
  ASSERT_EQ(once.rest_ids.size(), static_cast<size_t>(nv + ne));
  const double edge = MeanEdgeLength(s);
  double moved = 0.0;
  for (int v = 0; v < nv; ++v) {
    ASSERT_EQ(once.rest_ids[v], posed.rest_ids[v]) << v;
    moved = std::max(moved, (once.surface.V.row(v) - s.V.row(v)).norm());
  }
  EXPECT_GT(moved, 0.0);
  EXPECT_LT(moved, edge) << "Loop's rule moves a vertex by a fraction of its edges";
  for (int v = nv; v < nv + ne; ++v) ASSERT_EQ(once.rest_ids[v], -1) << v;
  EXPECT_NEAR(TotalArea(once.surface) / TotalArea(s), 1.0, 0.05);
  EXPECT_EQ(Subdivide(posed, 2).surface.NumFaces(), 16 * nf);
  EXPECT_EQ(Subdivide(posed, 0).surface.V, s.V);
}

TEST_P(SyntheticKinds, PartialShapesLoseOnePartAndKeepExactGroundTruth) {
  SynthOptions o = Options(GetParam(), 4, 1500);
  const SynthClass full = GenerateClass(GetParam(), o);
  o.partial = 0.5;
  const SynthClass cut = GenerateClass(GetParam(), o);
  int num_cut = 0;
  for (size_t p = 0; p < cut.shapes.size(); ++p) {
    const TrackedSurface& c = cut.shapes[p].shape;
    const Surface& f = full.shapes[p].shape.surface;
    if (c.surface.NumVertices() == f.NumVertices()) {
      EXPECT_TRUE(cut.shapes[p].note.empty());
      continue;
    }
    ++num_cut;
    EXPECT_EQ(cut.shapes[p].note.rfind("cut ", 0), 0u) << cut.shapes[p].note;
    const MeshReport t = ValidateMesh(c.surface, cut.shapes[p].name);
    EXPECT_EQ(t.boundary_loops, 1) << t.ToString();
    EXPECT_EQ(t.non_manifold_edges, 0) << t.ToString();
    EXPECT_EQ(t.non_manifold_vertices, 0) << t.ToString();
    EXPECT_EQ(t.inconsistent_edges, 0) << t.ToString();
    EXPECT_EQ(t.degenerate_faces, 0) << t.ToString();
    EXPECT_EQ(t.components, 1) << t.ToString();
    EXPECT_EQ(t.euler_characteristic, 1) << t.ToString();  // a disc
    // A hand, foot or head: a few percent of the surface, not more than a fifth.
    EXPECT_LT(f.NumVertices() - c.surface.NumVertices(), f.NumVertices() / 5);
    for (int v = 0; v < c.surface.NumVertices(); ++v) {
      ASSERT_TRUE(c.surface.V.row(v) == f.V.row(c.rest_ids[v])) << v;
    }
  }
  EXPECT_EQ(num_cut, 2);
}

TEST_P(SyntheticKinds, GluedPosesShortCircuitTheSurfaceAndKeepTheirVertices) {
  SynthOptions o = Options(GetParam(), 4, 1500);
  o.glue = 0.5;
  o.glue_bridges = 0;
  const SynthClass control = GenerateClass(GetParam(), o);
  o.glue_bridges = 8;
  const SynthClass glued = GenerateClass(GetParam(), o);
  const int rest_vertices = glued.rest.surface.NumVertices();
  int num_glued = 0;
  for (size_t p = 0; p < glued.shapes.size(); ++p) {
    const Surface& g = glued.shapes[p].shape.surface;
    const Surface& c = control.shapes[p].shape.surface;
    // Gluing changes the faces only: the same vertices, at the same (contact) positions.
    ASSERT_EQ(g.NumVertices(), rest_vertices);
    ASSERT_TRUE(g.V == c.V) << glued.shapes[p].name;
    EXPECT_EQ(glued.shapes[p].shape.rest_ids, control.shapes[p].shape.rest_ids);
    if (g.NumFaces() == c.NumFaces()) {
      EXPECT_EQ(glued.shapes[p].note.find("glued"), std::string::npos);
      continue;
    }
    ++num_glued;
    EXPECT_NE(glued.shapes[p].note.find("contact pose"), std::string::npos);
    EXPECT_NE(control.shapes[p].note.find("contact pose"), std::string::npos);
    // Closed, manifold and consistently oriented, with one handle per tube.
    const int tubes = (g.NumFaces() - c.NumFaces()) / 4;
    const MeshReport report = ValidateMesh(g, glued.shapes[p].name);
    EXPECT_TRUE(report.clean()) << report.ToString();
    EXPECT_TRUE(report.closed_manifold) << report.ToString();
    EXPECT_EQ(report.components, 1) << report.ToString();
    EXPECT_EQ(report.genus, tubes) << report.ToString();
    // A short circuit: some pair of vertices is far closer along the glued surface's edges than
    // along the control's. Every tube edge is such a pair.
    double shortest_ratio = 1.0;
    for (int f = c.NumFaces() - 2 * tubes; f < g.NumFaces(); ++f) {
      if (f < 0) continue;
      const int a = g.F(f, 0), b = g.F(f, 1);
      const std::vector<double> dg = Dijkstra(g, a), dc = Dijkstra(c, a);
      shortest_ratio = std::min(shortest_ratio, dg[b] / dc[b]);
    }
    EXPECT_LT(shortest_ratio, 0.34) << glued.shapes[p].name;
  }
  EXPECT_EQ(num_glued, 2);
  // A contact pose is drawn for its own pose, never another pose of the class.
  for (size_t p = 0; p < glued.shapes.size(); ++p) {
    for (size_t q = 0; q < p; ++q) {
      EXPECT_FALSE(control.shapes[p].shape.surface.V == control.shapes[q].shape.surface.V)
          << p << " " << q;
    }
  }
}

TEST_P(SyntheticKinds, HolesAndPlaneCutsRemoveSurfaceAndKeepExactGroundTruth) {
  SynthOptions o = Options(GetParam(), 6, 1500);
  const SynthClass full = GenerateClass(GetParam(), o);
  for (const char* mode : {"holes", "plane_cuts"}) {
    SynthOptions m = o;
    (std::string(mode) == "holes" ? m.holes : m.plane_cuts) = 0.5;
    const SynthClass cut = GenerateClass(GetParam(), m);
    int changed = 0;
    for (size_t p = 0; p < cut.shapes.size(); ++p) {
      const TrackedSurface& c = cut.shapes[p].shape;
      const Surface& f = full.shapes[p].shape.surface;
      if (c.surface.NumVertices() == f.NumVertices()) continue;
      ++changed;
      const MeshReport t = ValidateMesh(c.surface, cut.shapes[p].name);
      EXPECT_GE(t.boundary_loops, 1) << t.ToString();
      EXPECT_EQ(t.non_manifold_edges, 0) << t.ToString();
      EXPECT_EQ(t.inconsistent_edges, 0) << t.ToString();
      EXPECT_EQ(t.components, 1) << t.ToString();
      const double removed = 1.0 - static_cast<double>(c.surface.NumVertices()) / f.NumVertices();
      if (std::string(mode) == "plane_cuts") {
        EXPECT_NE(cut.shapes[p].note.find("plane cut"), std::string::npos);
        // 10-40% below the plane, and what the largest piece leaves of the rest.
        EXPECT_GE(removed, 0.1 - 0.02) << cut.shapes[p].name;
        EXPECT_LE(removed, 0.7) << cut.shapes[p].name;
      } else {
        EXPECT_NE(cut.shapes[p].note.find("hole"), std::string::npos);
        EXPECT_GT(removed, 0.0);
        EXPECT_LT(removed, 0.6) << cut.shapes[p].name;
      }
      for (int v = 0; v < c.surface.NumVertices(); ++v) {
        ASSERT_TRUE(c.surface.V.row(v) == f.V.row(c.rest_ids[v])) << v;
      }
    }
    EXPECT_EQ(changed, 3) << mode;
  }
  // Off, the options leave the text (and so every cache folder named by its hash) as it was.
  EXPECT_EQ(SynthOptionsText(o).find("glue"), std::string::npos);
  EXPECT_EQ(SynthOptionsText(o).find("holes"), std::string::npos);
  EXPECT_EQ(SynthOptionsText(o).find("plane_cuts"), std::string::npos);
}

// The cross class: another body plan on the same mesh (so rest vertex ids, faces and the mirror
// map carry over), exactly symmetric at rest, bent forwards, and far less isometric to the base
// class than the base class's own poses are to each other.
TEST_P(SyntheticKinds, CrossClassBodiesShareTheMeshButNotTheProportions) {
  SynthOptions o = Options(GetParam(), 3, 1500);
  const SynthClass base = GenerateClass(GetParam(), o);
  EXPECT_THROW(GenerateClass(GetParam(), o, ClassBody::kCross), ConfigError);
  o.cross_class = 0.3;
  const SynthClass cross = GenerateClass(GetParam(), o, ClassBody::kCross);
  EXPECT_EQ(cross.name, FigureKindName(GetParam()) + "_cross");
  const Surface& rest = cross.rest.surface;
  ASSERT_TRUE(rest.F == base.rest.surface.F);
  EXPECT_EQ(cross.rest.mirror, base.rest.mirror);
  for (int i = 0; i < rest.NumVertices(); ++i) {
    const int m = cross.rest.mirror[i];
    ASSERT_TRUE(rest.V(m, 0) == -rest.V(i, 0) && rest.V(m, 1) == rest.V(i, 1) &&
                rest.V(m, 2) == rest.V(i, 2)) << i;
  }
  // Bent forwards: the highest point moves forwards by R/2 of the height, the lowest not at all.
  int top = 0, bottom = 0;
  base.rest.surface.V.col(1).maxCoeff(&top);
  base.rest.surface.V.col(1).minCoeff(&bottom);
  const double height = base.rest.surface.V(top, 1) - base.rest.surface.V(bottom, 1);
  EXPECT_NEAR(rest.V(top, 2) - base.rest.surface.V(top, 2), 0.15 * height, 1e-12);
  EXPECT_EQ(rest.V(bottom, 2), base.rest.surface.V(bottom, 2));
  // Its poses are its own (another stream) and keep the identity ground truth.
  for (size_t p = 0; p < cross.shapes.size(); ++p) {
    EXPECT_EQ(cross.shapes[p].name, cross.name + std::to_string(p));
    ExpectClosedGenusZero(cross.shapes[p].shape.surface, cross.shapes[p].name);
    EXPECT_GT(SignedVolume(cross.shapes[p].shape.surface), 0.0);
    EXPECT_FALSE(cross.shapes[p].shape.surface.V == base.shapes[p].shape.surface.V);
  }
  // Mean relative change of edge-graph distances (in units of each shape's sqrt(area)) from 8
  // sources: between the classes at least twice that within the base class.
  auto change = [](const Surface& a, const Surface& b) {
    return MeanRelativeDistanceChange(a, b, std::sqrt(FaceAreas(a).sum()),
                                      std::sqrt(FaceAreas(b).sum()));
  };
  const double within = change(base.shapes[0].shape.surface, base.shapes[1].shape.surface);
  const double across = change(base.shapes[0].shape.surface, cross.shapes[1].shape.surface);
  RecordProperty("within", std::to_string(within));
  RecordProperty("across", std::to_string(across));
  EXPECT_GT(across, 2.0 * within);
  // Pairs cross the classes: every pose onto every pose, or a seeded subset, in order.
  EXPECT_EQ(CrossClassPairs(GetParam(), o).size(), 9u);
  o.pairs = 4;
  const auto some = CrossClassPairs(GetParam(), o);
  ASSERT_EQ(some.size(), 4u);
  EXPECT_TRUE(std::is_sorted(some.begin(), some.end()));
  EXPECT_EQ(some, CrossClassPairs(GetParam(), o));
}

TEST_P(SyntheticKinds, NoiseMovesVerticesAlongNormalsWithinTheAmplitude) {
  SynthOptions o = Options(GetParam(), 2, 1500);
  const SynthClass clean = GenerateClass(GetParam(), o);
  o.noise = 0.2;
  const SynthClass noisy = GenerateClass(GetParam(), o);
  for (size_t p = 0; p < clean.shapes.size(); ++p) {
    const Surface& a = clean.shapes[p].shape.surface;
    const Surface& b = noisy.shapes[p].shape.surface;
    const Eigen::MatrixX3d N = VertexNormals(a);
    const double limit = 0.2 * MeanEdgeLength(a);
    const Eigen::MatrixX3d D = b.V - a.V;
    double largest = 0.0;
    for (int v = 0; v < a.NumVertices(); ++v) {
      const Eigen::Vector3d d = D.row(v).transpose();
      largest = std::max(largest, d.norm());
      ASSERT_LE(d.norm(), limit * (1 + 1e-12));
      // Along the normal: the tangential part is rounding only.
      ASSERT_LT((d - d.dot(N.row(v).transpose()) * N.row(v).transpose()).norm(), 1e-12);
    }
    EXPECT_GT(largest, 0.5 * limit);
    EXPECT_TRUE(a.F == b.F);
  }
}

TEST(Synthetic, WrittenDatasetIsByteIdenticalForTheSameOptions) {
  testing::TempDir dir;
  SynthOptions o;
  o.kinds = {FigureKind::kHumanoid, FigureKind::kQuadruped};
  o.poses = 3;
  o.vertices = 1000;
  o.remesh = 600;
  o.partial = 0.4;
  o.noise = 0.05;
  o.nonisometric = 0.1;
  WriteSyntheticDataset(dir.File("a"), o);
  WriteSyntheticDataset(dir.File("b"), o);
  o.seed = 2;
  WriteSyntheticDataset(dir.File("c"), o);
  int files = 0, differ_with_seed = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir.File("a"))) {
    if (!entry.is_regular_file()) continue;
    const fs::path rel = fs::relative(entry.path(), dir.File("a"));
    const std::string a = testing::ReadText(entry.path().string());
    EXPECT_EQ(a, testing::ReadText(dir.File("b") + "/" + rel.string())) << rel;
    if (a != testing::ReadText(dir.File("c") + "/" + rel.string())) ++differ_with_seed;
    ++files;
  }
  EXPECT_EQ(files, 6 * 3 + 2);  // .off, .vts, .sym.vts per shape; test_pairs.txt; README.md
  EXPECT_GT(differ_with_seed, 12);
  const std::string readme = testing::ReadText(dir.File("a/README.md"));
  EXPECT_NE(readme.find("seed: 1"), std::string::npos);
  EXPECT_NE(readme.find("remesh: 600"), std::string::npos);
}

TEST(Synthetic, PairsVtsLoaderReadsTheWrittenGroundTruth) {
  testing::TempDir dir;
  SynthOptions o;
  o.poses = 4;
  o.vertices = 1000;
  o.remesh = 500;
  o.partial = 0.5;
  WriteSyntheticDataset(dir.path(), o);
  const SynthClass c = GenerateClass(FigureKind::kHumanoid, o);
  PairsVtsDataset loader(PairsVtsOptions{dir.path(), {}});
  const DatasetIndex index = loader.Load();
  ASSERT_EQ(index.shapes.size(), 4u);
  ASSERT_EQ(index.pairs.size(), 6u);
  EXPECT_EQ(index.pairs[0].source, "humanoid0");
  EXPECT_EQ(index.pairs[0].target, "humanoid1");
  const int num_rest = c.rest.surface.NumVertices();
  for (size_t p = 0; p < c.shapes.size(); ++p) {
    const DatasetShape* shape = index.Find(c.shapes[p].name);
    ASSERT_NE(shape, nullptr);
    EXPECT_EQ(shape->class_name, "humanoid");
    const TrackedSurface& t = c.shapes[p].shape;
    const ShapeGroundTruth gt = loader.GroundTruth(*shape, t.surface.NumVertices());
    ASSERT_EQ(static_cast<int>(gt.ids.size()), num_rest);
    ASSERT_EQ(gt.sym_ids.size(), gt.ids.size());
    int present = 0;
    for (int i = 0; i < num_rest; ++i) {
      if (gt.ids[i] >= 0) {
        ASSERT_EQ(t.rest_ids[gt.ids[i]], i);
        ++present;
      }
      if (gt.sym_ids[i] >= 0) {
        ASSERT_EQ(t.rest_ids[gt.sym_ids[i]], c.rest.mirror[i]);
      }
    }
    EXPECT_EQ(present, t.surface.NumVertices());
  }
  // Pair lines: the rest vertices both shapes kept.
  const InputGroundTruth pair = PairLines(loader.GroundTruth(*index.Find("humanoid0"), 500),
                                         loader.GroundTruth(*index.Find("humanoid1"), 500));
  EXPECT_GT(pair.source_ids.size(), 50u);
}

TEST(Synthetic, InvalidOptionsAreRejected) {
  SynthOptions o;
  std::string error;
  EXPECT_TRUE(o.IsValid(&error));
  o.poses = 0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("poses"), std::string::npos);
  o = SynthOptions();
  o.nonisometric = 0.7;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("nonisometric"), std::string::npos);
  o = SynthOptions();
  o.remesh_anisotropy = 3.0;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("needs remesh"), std::string::npos);
  o.remesh = 500;
  EXPECT_TRUE(o.IsValid(&error));
  o.remesh_anisotropy = 0.5;
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_NE(error.find("remesh_anisotropy"), std::string::npos);
  o = SynthOptions();
  o.kinds = {};
  EXPECT_FALSE(o.IsValid(&error));
  EXPECT_THROW(GenerateClass(FigureKind::kHumanoid, o), ConfigError);
  EXPECT_THROW(FigureKindFromName("horse"), ConfigError);
}

TEST(Synthetic, RandomNumbersArePlatformIndependent) {
  // std::mt19937's sequence is fixed by the standard (its 10000th output is 4123659995);
  // the conversions on top are integer arithmetic, so these values are the same everywhere.
  std::mt19937 engine(5489u);
  engine.discard(9999);
  EXPECT_EQ(engine(), 4123659995u);
  SynthRandom random(42);
  const double u = random.Uniform();
  EXPECT_GE(u, 0.0);
  EXPECT_LT(u, 1.0);
  SynthRandom again(42);
  EXPECT_EQ(again.Uniform(), u);
  for (int i = 0; i < 1000; ++i) {
    const int k = random.Index(7);
    ASSERT_GE(k, 0);
    ASSERT_LT(k, 7);
  }
  EXPECT_NE(DeriveSeed(1, "angles", 0, 1), DeriveSeed(1, "angles", 0, 2));
  EXPECT_NE(DeriveSeed(1, "angles", 0, 1), DeriveSeed(1, "scales", 0, 1));
}

TEST(Synthetic, CommandWritesADatasetAndRejectsBadArguments) {
  testing::TempDir dir;
  const std::string bin = SYMEMBED_BINARY;
  std::string out;
  ASSERT_EQ(testing::RunShell(bin + " synth --kind quadruped --poses 2 --vertices 800 --out " +
                                  dir.File("q"), &out), 0) << out;
  EXPECT_TRUE(fs::exists(dir.File("q/shapes/quadruped1.off")));
  EXPECT_TRUE(fs::exists(dir.File("q/corres/quadruped0.sym.vts")));
  EXPECT_EQ(testing::ReadText(dir.File("q/test_pairs.txt")), "quadruped0\tquadruped1\n");
  // Not empty now: refused without --force, replaced with it.
  EXPECT_EQ(testing::RunShell(bin + " synth --poses 2 --vertices 800 --out " + dir.File("q"), &out), 1);
  EXPECT_NE(out.find("--force"), std::string::npos) << out;
  EXPECT_EQ(testing::RunShell(bin + " synth --poses 2 --vertices 800 --force --out " + dir.File("q"), &out), 0) << out;
  EXPECT_TRUE(fs::exists(dir.File("q/shapes/humanoid1.off")));
  EXPECT_FALSE(fs::exists(dir.File("q/shapes/quadruped1.off")));
  EXPECT_EQ(testing::RunShell(bin + " synth --kind horse --out " + dir.File("h"), &out), 2);
  EXPECT_NE(out.find("--kind"), std::string::npos) << out;
  EXPECT_EQ(testing::RunShell(bin + " synth --poses 2 --noise -1 --out " + dir.File("h"), &out), 2);
  EXPECT_NE(out.find("noise"), std::string::npos) << out;
  EXPECT_EQ(testing::RunShell(bin + " synth --poses 2", &out), 2);
  EXPECT_EQ(testing::RunShell(bin + " synth --poses 2 --cross-class 0.5 --out " + dir.File("h"), &out), 2);
  EXPECT_NE(out.find("cross_class"), std::string::npos) << out;
  ASSERT_EQ(testing::RunShell(bin + " synth --poses 2 --vertices 800 --cross-class 0.2 --out " +
                                  dir.File("x"), &out), 0) << out;
  EXPECT_EQ(testing::ReadText(dir.File("x/test_pairs.txt")),
            "humanoid0\thumanoid_cross0\nhumanoid0\thumanoid_cross1\n"
            "humanoid1\thumanoid_cross0\nhumanoid1\thumanoid_cross1\n");
  EXPECT_TRUE(fs::exists(dir.File("x/corres/humanoid_cross1.sym.vts")));
}

INSTANTIATE_TEST_SUITE_P(Kinds, SyntheticKinds,
                         ::testing::Values(FigureKind::kHumanoid, FigureKind::kQuadruped),
                         [](const ::testing::TestParamInfo<FigureKind>& info) {
                           return FigureKindName(info.param);
                         });

}  // namespace
}  // namespace symembed

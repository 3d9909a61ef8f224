#include "core/handles.h"

#include <gtest/gtest.h>

#include <cmath>

#include "core/mesh_graph.h"
#include "core/primitives.h"
#include "core/validation.h"
#include "eval/synthetic/synthetic.h"

namespace symembed {
namespace {

// A torus of tube radius r around a circle of radius R: n x m quads split in two.
Surface Torus(int n, int m, double R, double r) {
  Surface s;
  s.V.resize(n * m, 3);
  s.F.resize(2 * n * m, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      s.V.row(i * m + j) << (R + r * std::cos(v)) * std::cos(u),
          (R + r * std::cos(v)) * std::sin(u), r * std::sin(v);
      const int a = i * m + j, b = ((i + 1) % n) * m + j, c = ((i + 1) % n) * m + (j + 1) % m,
                d = i * m + (j + 1) % m;
      s.F.row(2 * (i * m + j)) << a, b, c;
      s.F.row(2 * (i * m + j) + 1) << a, c, d;
    }
  }
  return s;
}

std::vector<int> FacesPerVertex(const Surface& s) {
  std::vector<int> count(s.NumVertices(), 0);
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) ++count[s.F(f, k)];
  }
  return count;
}

double GraphDistance(const Surface& s, int a, int b) {
  const MeshGraph graph = BuildMeshGraph(s);
  std::vector<double> dist(s.NumVertices());
  DijkstraWorkspace<double> workspace;
  Dijkstra(graph, a, dist.data(), &workspace);
  return dist[b];
}

TEST(Handles, GenusZeroIsLeftAlone) {
  const Surface sphere = Icosphere(3);
  EXPECT_EQ(SurfaceGenus(sphere), 0);
  const HandleCutResult r = CutHandles(sphere);
  EXPECT_EQ(r.genus_before, 0);
  EXPECT_EQ(r.cuts, 0);
  EXPECT_TRUE(r.F == sphere.F);
  // A disc with holes is genus 0 too: a loop around a hole is not a handle.
  const Surface grid = GridMesh(10, 10);
  EXPECT_EQ(SurfaceGenus(grid), 0);
  EXPECT_EQ(CutHandles(grid).cuts, 0);
}

TEST(Handles, ATorusIsCutAroundItsTubeKeepingEveryVertex) {
  const Surface torus = Torus(48, 12, 1.0, 0.25);
  EXPECT_EQ(SurfaceGenus(torus), 1);
  HandleCutOptions open;
  open.cap = false;
  const HandleCutResult r = CutHandles(torus, open);
  EXPECT_EQ(r.genus_before, 1);
  EXPECT_EQ(r.genus_after, 0);
  EXPECT_EQ(r.cuts, 1);
  EXPECT_EQ(r.removed_faces, torus.NumFaces() - r.F.rows());
  EXPECT_GT(r.removed_faces, 0);
  EXPECT_LT(r.removed_faces, 4 * 12);  // a strip along one short loop
  // The short loop around the tube (2 pi 0.25 = 1.57), not the long one around the hole (6.28).
  EXPECT_LT(r.longest_loop, 2.0);
  Surface cut = torus;
  cut.F = r.F;
  for (int n : FacesPerVertex(cut)) EXPECT_GT(n, 0);
  const MeshReport report = ValidateMesh(cut, "cut torus");
  EXPECT_EQ(report.components, 1) << report.ToString();
  EXPECT_EQ(report.boundary_loops, 2) << report.ToString();
  EXPECT_EQ(SurfaceGenus(cut), 0);
  EXPECT_EQ(r.capped_loops, 0);
}

TEST(Handles, TheLoopsACutOpensAreClosedWithoutNewVertices) {
  const Surface torus = Torus(48, 12, 1.0, 0.25);
  HandleCutOptions open;
  open.cap = false;
  const HandleCutResult cut = CutHandles(torus, open);
  const HandleCutResult r = CutHandles(torus);
  EXPECT_EQ(r.cuts, 1);
  EXPECT_EQ(r.removed_faces, cut.removed_faces);
  EXPECT_EQ(r.capped_loops, 2);
  // The faces kept come first, as without capping; each loop of n vertices gets n - 2 faces.
  ASSERT_EQ(r.F.rows(), cut.F.rows() + r.cap_faces);
  EXPECT_TRUE(r.F.topRows(cut.F.rows()) == cut.F);
  EXPECT_GT(r.cap_faces, 0);
  Surface closed = torus;
  closed.F = r.F;
  const MeshReport report = ValidateMesh(closed, "capped torus");
  EXPECT_EQ(report.components, 1) << report.ToString();
  EXPECT_EQ(report.boundary_loops, 0) << report.ToString();
  EXPECT_EQ(report.non_manifold_edges, 0) << report.ToString();
  EXPECT_EQ(SurfaceGenus(closed), 0);
  // Each cap runs its loop against the kept faces: the orientation stays consistent.
  EXPECT_EQ(report.inconsistent_edges, 0) << report.ToString();
  EXPECT_EQ(report.non_manifold_vertices, 0) << report.ToString();
  // A surface whose handle is not cut gets no cap: the open grid keeps its boundary.
  EXPECT_EQ(CutHandles(GridMesh(10, 10)).capped_loops, 0);
}

class GluedKinds : public ::testing::TestWithParam<FigureKind> {};

TEST_P(GluedKinds, GluedLimbsLoseTheirShortCircuit) {
  SynthOptions o;
  o.kinds = {GetParam()};
  o.poses = 4;
  o.vertices = 1500;
  o.glue = 0.5;
  o.glue_bridges = 0;
  const SynthClass control = GenerateClass(GetParam(), o);
  o.glue_bridges = 8;
  const SynthClass glued = GenerateClass(GetParam(), o);
  int checked = 0;
  for (size_t p = 0; p < glued.shapes.size(); ++p) {
    const Surface& g = glued.shapes[p].shape.surface;
    const Surface& c = control.shapes[p].shape.surface;
    const int tubes = (g.NumFaces() - c.NumFaces()) / 4;
    if (tubes == 0) continue;
    ++checked;
    const HandleCutResult r = CutHandles(g);
    EXPECT_EQ(r.genus_before, tubes);
    EXPECT_EQ(r.genus_after, 0);
    Surface cut = g;
    cut.F = r.F;
    // A strip may leave a vertex of a thin bridge without faces, not more than a few.
    int isolated = 0;
    for (int n : FacesPerVertex(cut)) isolated += n == 0;
    EXPECT_EQ(isolated, r.removed_vertices);
    EXPECT_LE(isolated, 3 * tubes);
    // Across a tube (its faces are the last 6 per tube), the body's vertices next to its two
    // ends are at least half the control's distance apart along the cut surface once its short
    // circuit is gone (the tube's own end vertices may stay on it, cut off from the body).
    // Known limit (docs/failure-modes.md): where tubes sit side by side, a loop through two of
    // them is as short as a loop around one; of the shortest loops the cut that separates most
    // is taken, which severs all but at most one tube here (the humanoids: all).
    std::vector<char> on_tube(g.NumVertices(), 0);
    for (int f = g.NumFaces() - 6 * tubes; f < g.NumFaces(); ++f) {
      for (int k = 0; k < 3; ++k) on_tube[g.F(f, k)] = 1;
    }
    const MeshGraph control_graph = BuildMeshGraph(c);
    auto body_neighbour = [&](int v) {
      for (int i = control_graph.offsets[v]; i < control_graph.offsets[v + 1]; ++i) {
        if (!on_tube[control_graph.neighbors[i]]) return control_graph.neighbors[i];
      }
      return -1;
    };
    int short_circuited = 0;
    for (int tube = 0; tube < tubes; ++tube) {
      bool short_circuit = false;
      for (int f = g.NumFaces() - 6 * (tubes - tube); f < g.NumFaces() - 6 * (tubes - tube - 1);
           ++f) {
        for (int k = 0; k < 3; ++k) {
          const int a = body_neighbour(g.F(f, k)), b = body_neighbour(g.F(f, (k + 1) % 3));
          if (a < 0 || b < 0 || a == b) continue;  // an end surrounded by tubes
          short_circuit |= GraphDistance(cut, a, b) < 0.5 * GraphDistance(c, a, b);
        }
      }
      short_circuited += short_circuit;
    }
    EXPECT_LE(short_circuited, 1) << glued.shapes[p].name << ": " << tubes << " tubes";
    if (GetParam() == FigureKind::kHumanoid) {
      EXPECT_EQ(short_circuited, 0) << glued.shapes[p].name;
    }
  }
  EXPECT_EQ(checked, 2);
}

INSTANTIATE_TEST_SUITE_P(Kinds, GluedKinds,
                         ::testing::Values(FigureKind::kHumanoid, FigureKind::kQuadruped),
                         [](const auto& info) { return FigureKindName(info.param); });

TEST(Handles, AHoleBesideAHandleIsNotTakenForOne) {
  // The torus with a hole cut into its outer side: still genus 1, one boundary loop.
  Surface torus = Torus(48, 12, 1.0, 0.25);
  Eigen::MatrixX3i kept(torus.NumFaces() - 8, 3);
  for (int f = 0, row = 0; f < torus.NumFaces(); ++f) {
    const bool hole = f / 24 >= 10 && f / 24 < 12 && f % 24 < 4;  // 2 x 2 quads
    if (!hole) kept.row(row++) = torus.F.row(f);
  }
  torus.F = kept;
  EXPECT_EQ(SurfaceGenus(torus), 1);
  const HandleCutResult r = CutHandles(torus);
  EXPECT_EQ(r.cuts, 1);
  EXPECT_EQ(r.genus_after, 0);
  EXPECT_LT(r.longest_loop, 2.0);
}

TEST(Handles, ANonManifoldSurfaceIsNotSearched) {
  Surface s = Torus(24, 8, 1.0, 0.25);
  s.F.conservativeResize(s.NumFaces() + 1, 3);
  s.F.row(s.NumFaces() - 1) = s.F.row(0);  // the same face twice
  const HandleCutResult r = CutHandles(s);
  EXPECT_EQ(r.genus_before, -1);
  EXPECT_EQ(r.cuts, 0);
  EXPECT_FALSE(r.skipped.empty());
}

}  // namespace
}  // namespace symembed

#include "stages/preprocess/standard.h"

#include <gtest/gtest.h>

#include <limits>
#include <map>

#include "core/errors.h"
#include "core/handles.h"
#include "core/primitives.h"
#include "core/validation.h"
#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"

namespace symembed {
namespace {

double Get(const Report& report, const std::string& key) {
  for (const auto& [k, v] : report) {
    if (k == key) return v;
  }
  ADD_FAILURE() << "missing report key " << key;
  return -1;
}

double SignedVolume(const Surface& s) {
  double vol = 0.0;
  for (int f = 0; f < s.NumFaces(); ++f) {
    const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
    vol += a.dot(b.cross(c)) / 6.0;
  }
  return vol;
}

// True when every interior edge is run in opposite directions by its two faces.
bool ConsistentlyOriented(const Surface& s) {
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (++directed[{s.F(f, k), s.F(f, (k + 1) % 3)}] > 1) return false;
    }
  }
  return true;
}

Surface Append(const Surface& a, const Surface& b, const Eigen::RowVector3d& offset) {
  Surface s;
  s.V.resize(a.NumVertices() + b.NumVertices(), 3);
  s.V << a.V, b.V.rowwise() + offset;
  s.F.resize(a.NumFaces() + b.NumFaces(), 3);
  s.F << a.F, (b.F.array() + a.NumVertices()).matrix();
  return s;
}

TEST(StandardPreprocess, RestoresOutwardOrientation) {
  Surface sphere = Icosphere(3, 2.0);
  int flipped = 0;
  for (int f = 0; f < sphere.NumFaces(); f += 7, ++flipped) {
    std::swap(sphere.F(f, 1), sphere.F(f, 2));
  }
  const PreprocessResult r = StandardPreprocess(sphere);
  EXPECT_EQ(Get(r.report, "flipped_faces"), flipped);
  EXPECT_EQ(Get(r.report, "orientation_conflicts"), 0);
  EXPECT_TRUE(ConsistentlyOriented(r.surface));
  EXPECT_GT(SignedVolume(r.surface), 0.0);

  // Entirely inside-out: every face is flipped back.
  Surface inverted = Icosphere(2);
  inverted.F.col(1).swap(inverted.F.col(2));
  const PreprocessResult ri = StandardPreprocess(inverted);
  EXPECT_EQ(Get(ri.report, "flipped_faces"), inverted.NumFaces());
  EXPECT_GT(SignedVolume(ri.surface), 0.0);
}

TEST(StandardPreprocess, OpenSurfaceKeepsMajorityOrientation) {
  Surface grid = GridMesh(10, 10);
  for (int f = 0; f < grid.NumFaces(); f += 5) std::swap(grid.F(f, 1), grid.F(f, 2));
  const PreprocessResult r = StandardPreprocess(grid);
  EXPECT_TRUE(ConsistentlyOriented(r.surface));
  EXPECT_EQ(Get(r.report, "flipped_faces"), (grid.NumFaces() + 4) / 5);
  EXPECT_EQ(Get(r.report, "boundary_edges"), 4 * 9);
  // Majority orientation of GridMesh is counter-clockwise seen from +z.
  const Eigen::Vector3d e1 = r.surface.V.row(r.surface.F(0, 1)) - r.surface.V.row(r.surface.F(0, 0));
  const Eigen::Vector3d e2 = r.surface.V.row(r.surface.F(0, 2)) - r.surface.V.row(r.surface.F(0, 0));
  EXPECT_GT(e1.cross(e2).z(), 0.0);
}

TEST(StandardPreprocess, DropsDuplicateAndDegenerateFacesAndUnreferencedVertices) {
  const Surface sphere = Icosphere(2);
  Surface s;
  const int n = sphere.NumVertices();
  s.V.resize(n + 4, 3);
  s.V << sphere.V, Eigen::RowVector3d(5, 5, 5), Eigen::RowVector3d(6, 5, 5),
      Eigen::RowVector3d(7, 5, 5), Eigen::RowVector3d(9, 9, 9);  // collinear x3, isolated
  s.F.resize(sphere.NumFaces() + 4, 3);
  s.F << sphere.F, Eigen::RowVector3i(sphere.F(0, 0), sphere.F(0, 2), sphere.F(0, 1)),  // dup
      Eigen::RowVector3i(sphere.F(3, 1), sphere.F(3, 2), sphere.F(3, 0)),                // dup
      Eigen::RowVector3i(0, 0, 1),                                                       // repeat
      Eigen::RowVector3i(n, n + 1, n + 2);                                               // zero area
  const PreprocessResult r = StandardPreprocess(s);
  EXPECT_EQ(Get(r.report, "duplicate_faces"), 2);
  EXPECT_EQ(Get(r.report, "degenerate_faces"), 2);
  EXPECT_EQ(Get(r.report, "unreferenced_vertices"), 4);
  EXPECT_EQ(r.surface.NumFaces(), sphere.NumFaces());
  EXPECT_EQ(r.surface.NumVertices(), n);
  EXPECT_EQ(Get(r.report, "orientation_conflicts"), 0);
  EXPECT_EQ(Get(r.report, "non_manifold_edges"), 0);
}

TEST(StandardPreprocess, KeepsLargestComponentAndMapsIds) {
  const Surface small = Icosphere(1, 0.1), big = Icosphere(2, 1.0);
  const Surface s = Append(small, big, Eigen::RowVector3d(4, 0, 0));
  const PreprocessResult r = StandardPreprocess(s);
  EXPECT_EQ(Get(r.report, "components"), 2);
  EXPECT_EQ(Get(r.report, "removed_component_faces"), small.NumFaces());
  EXPECT_NEAR(Get(r.report, "removed_component_area"),
              TotalArea(small) / (TotalArea(small) + TotalArea(big)), 1e-12);
  ASSERT_EQ(r.surface.NumVertices(), big.NumVertices());
  ASSERT_EQ(static_cast<int>(r.input_ids.size()), big.NumVertices());
  // Unit area, centred, and output = (input - centre) * scale through input_ids.
  EXPECT_NEAR(TotalArea(r.surface), 1.0, 1e-12);
  const Eigen::RowVector3d centre(Get(r.report, "centre_x"), Get(r.report, "centre_y"),
                                  Get(r.report, "centre_z"));
  EXPECT_NEAR(centre.x(), 4.0, 1e-9);  // the icosphere is symmetric about its centre
  for (int i = 0; i < r.surface.NumVertices(); ++i) {
    EXPECT_EQ(r.input_ids[i], small.NumVertices() + i);
    EXPECT_LT((r.surface.V.row(i) - (s.V.row(r.input_ids[i]) - centre) * r.scale).norm(), 1e-12);
  }
  EXPECT_NEAR(r.scale, 1.0 / std::sqrt(TotalArea(big)), 1e-12);
}

TEST(StandardPreprocess, SurvivesNonManifoldEdge) {
  // Three triangles on one edge (a fin): OpenMesh cannot represent this mesh.
  Surface s;
  s.V.resize(5, 3);
  s.V << 0, 0, 0, 1, 0, 0, 0.5, 1, 0, 0.5, -1, 0, 0.5, 0, 1;
  s.F.resize(3, 3);
  s.F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  const PreprocessResult r = StandardPreprocess(s);
  EXPECT_EQ(Get(r.report, "non_manifold_edges"), 1);
  EXPECT_EQ(r.surface.NumFaces(), 3);
  EXPECT_EQ(Get(r.report, "components"), 1);
}

TEST(StandardPreprocess, RejectsBadInputAndIsRegistered) {
  Surface bad = Icosphere(0);
  bad.F(0, 0) = 99;
  EXPECT_THROW(StandardPreprocess(bad), InvalidInputError);
  Surface nan = Icosphere(0);
  nan.V(0, 0) = std::nan("");
  EXPECT_THROW(StandardPreprocess(nan), InvalidInputError);
  Registry registry;
  RegisterBuiltinStages(registry);
  auto stage = registry.CreateAs<PreprocessStage>(
      "preprocess", YAML::Load("{type: standard, normalize: false}"), "t.yaml",
      "pipeline.preprocess");
  const Surface sphere = Icosphere(2, 3.0);
  const PreprocessResult r = stage->Run(sphere);
  EXPECT_EQ(r.scale, 1.0);
  EXPECT_LT((r.surface.V - sphere.V).cwiseAbs().maxCoeff(), 1e-15);
}

}  // namespace
}  // namespace symembed

namespace symembed {
namespace {

// A body split in two: keeping one half would silently drop half the surface.
TEST(StandardPreprocess, FailsWhenKeepingTheLargestComponentRemovesMuchOfTheArea) {
  const Surface s = Append(Icosphere(2, 0.9), Icosphere(2, 1.0), Eigen::RowVector3d(4, 0, 0));
  try {
    StandardPreprocess(s);
    ADD_FAILURE() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("2 connected components and keeping the largest would "
                                         "remove 44."),
              std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("% of its area"), std::string::npos) << e.what();
  }
  StandardPreprocessOptions loose;
  loose.max_removed_area = 0.5;
  EXPECT_NEAR(Get(StandardPreprocess(s, loose).report, "removed_component_area"), 0.81 / 1.81,
              0.01);
}

// Every face with its own three vertices (as some OFF/OBJ/PLY writers store a mesh): the
// boundary copies are welded back into the original surface.
TEST(StandardPreprocess, WeldsATriangleSoup) {
  const Surface sphere = Icosphere(2);
  Surface soup;
  soup.V.resize(3 * sphere.NumFaces(), 3);
  soup.F.resize(sphere.NumFaces(), 3);
  for (int f = 0; f < sphere.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      soup.V.row(3 * f + k) = sphere.V.row(sphere.F(f, k));
      soup.F(f, k) = 3 * f + k;
    }
  }
  const PreprocessResult r = StandardPreprocess(soup);
  EXPECT_EQ(Get(r.report, "welded_vertices"), soup.NumVertices() - sphere.NumVertices());
  EXPECT_EQ(r.surface.NumVertices(), sphere.NumVertices());
  EXPECT_EQ(r.surface.NumFaces(), sphere.NumFaces());
  EXPECT_EQ(Get(r.report, "components"), 1);
  EXPECT_EQ(Get(r.report, "boundary_edges"), 0);
  StandardPreprocessOptions no_weld;
  no_weld.weld_boundary_duplicates = false;
  no_weld.max_removed_area = 1.0;
  EXPECT_EQ(StandardPreprocess(soup, no_weld).surface.NumFaces(), 1);
}

// Two closed spheres touching at one point, each with its own vertex there: the copies are
// inside the surface and stay apart.
TEST(StandardPreprocess, LeavesCoincidentInteriorVerticesApart) {
  const Surface a = Icosphere(1, 1.0);
  int top = 0;
  a.V.col(0).maxCoeff(&top);
  const Eigen::RowVector3d offset(2 * a.V(top, 0), 0, 0);
  Surface mirrored = a;
  mirrored.V.col(0) *= -1;
  for (int f = 0; f < mirrored.NumFaces(); ++f) std::swap(mirrored.F(f, 1), mirrored.F(f, 2));
  const Surface s = Append(a, mirrored, offset);
  StandardPreprocessOptions options;
  options.max_removed_area = 1.0;
  const PreprocessResult r = StandardPreprocess(s, options);
  EXPECT_EQ(Get(r.report, "welded_vertices"), 0);
  EXPECT_EQ(Get(r.report, "components"), 2);
}

TEST(StandardPreprocess, NamesTheVertexWithNonFiniteCoordinates) {
  Surface s = Icosphere(1);
  s.V(7, 1) = std::numeric_limits<double>::quiet_NaN();
  try {
    StandardPreprocess(s);
    ADD_FAILURE() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 7 (0-based) has non-finite coordinates"),
              std::string::npos)
        << e.what();
  }
}

TEST(StandardPreprocess, CutsTheHandlesOfAGluedBody) {
  SynthOptions o;
  o.poses = 2;
  o.vertices = 1500;
  o.glue = 1.0;
  const SynthClass glued = GenerateClass(FigureKind::kHumanoid, o);
  const Surface& body = glued.shapes[0].shape.surface;
  const int genus = SurfaceGenus(body);
  ASSERT_GT(genus, 0) << glued.shapes[0].note;
  const PreprocessResult r = StandardPreprocess(body);
  EXPECT_EQ(Get(r.report, "genus"), genus);
  EXPECT_EQ(Get(r.report, "handles_cut"), genus);
  EXPECT_GT(Get(r.report, "handle_faces_removed"), 0);
  EXPECT_EQ(r.surface.NumVertices(), body.NumVertices() - Get(r.report, "handle_vertices_removed"));
  EXPECT_LE(Get(r.report, "handle_vertices_removed"), 3 * genus);
  EXPECT_EQ(SurfaceGenus(r.surface), 0);
  // The loops the cuts opened are closed, but for one that runs through a vertex twice (two
  // strips that touch), which stays open: the body has (nearly) no hole left.
  StandardPreprocessOptions open;
  open.cap_cut_handles = false;
  const PreprocessResult opened = StandardPreprocess(body, open);
  EXPECT_EQ(Get(opened.report, "handle_loops_capped"), 0);
  EXPECT_EQ(opened.surface.NumFaces(),
            body.NumFaces() - Get(opened.report, "handle_faces_removed"));
  const MeshReport with_caps = ValidateMesh(r.surface, "cut body");
  const int loops = ValidateMesh(opened.surface, "cut body").boundary_loops;
  EXPECT_GE(loops, genus);
  EXPECT_GE(Get(r.report, "handle_loops_capped"), loops - 1);
  EXPECT_EQ(with_caps.boundary_loops, loops - Get(r.report, "handle_loops_capped"));
  EXPECT_EQ(with_caps.non_manifold_edges, 0);
  EXPECT_EQ(with_caps.inconsistent_edges, 0);

  StandardPreprocessOptions off;
  off.cut_handles = false;
  const PreprocessResult kept = StandardPreprocess(body, off);
  EXPECT_EQ(Get(kept.report, "genus"), genus);
  EXPECT_EQ(kept.surface.NumFaces(), body.NumFaces());
  EXPECT_EQ(SurfaceGenus(kept.surface), genus);
  // A genus-0 surface is left exactly as it was.
  const Surface sphere = Icosphere(2);
  StandardPreprocessOptions no_cut;
  no_cut.cut_handles = false;
  EXPECT_TRUE(StandardPreprocess(sphere).surface.F == StandardPreprocess(sphere, no_cut).surface.F);
  EXPECT_EQ(Get(StandardPreprocess(sphere).report, "handles_cut"), 0);
}

}  // namespace
}  // namespace symembed

// Mesh file round trips and the accepted variants of each format.
#include "core/mesh_io.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "core/errors.h"
#include "core/primitives.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::ReadText;
using testing::TempDir;
using testing::WriteText;

// An icosphere with irrational, seeded coordinates so that printing precision matters.
Surface RandomizedSphere() {
  Surface s = Icosphere(2);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (int i = 0; i < s.NumVertices(); ++i) {
    for (int k = 0; k < 3; ++k) s.V(i, k) = 123.456789 * (s.V(i, k) + jitter(rng));
  }
  return s;
}

Eigen::MatrixX3d RandomColors(int n) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  Eigen::MatrixX3d c(n, 3);
  for (int i = 0; i < n; ++i) c.row(i) << unit(rng), unit(rng), unit(rng);
  return c;
}

// Little-endian (or big-endian) byte packing for binary files built in the tests.
template <typename T>
void Put(std::string* out, T value, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &value, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  out->append(b, sizeof(T));
}

TEST(MeshIo, RoundTripEveryWritableFormatWithAndWithoutColors) {
  TempDir dir;
  const Surface s = RandomizedSphere();
  const Eigen::MatrixX3d colors = RandomColors(s.NumVertices());
  for (const std::string ext : {"off", "obj", "ply"}) {
    for (const bool with_colors : {false, true}) {
      SCOPED_TRACE(ext + (with_colors ? " with colours" : ""));
      const std::string path = dir.File("mesh." + ext);
      SaveMesh(path, s, with_colors ? &colors : nullptr);
      Eigen::MatrixX3d read_colors;
      const Surface r = LoadSurface(path, &read_colors);
      // Numbers are written in shortest round-trip form, so positions come back exactly.
      EXPECT_EQ(r.V, s.V);
      EXPECT_EQ(r.F, s.F);
      if (!with_colors) {
        EXPECT_EQ(read_colors.rows(), 0);
        continue;
      }
      ASSERT_EQ(read_colors.rows(), s.NumVertices());
      // OFF and PLY store 0-255 bytes: rounding error at most half a step; OBJ stores reals.
      const double tolerance = ext == "obj" ? 0.0 : 0.5 / 255.0 + 1e-12;
      EXPECT_LE((read_colors - colors).cwiseAbs().maxCoeff(), tolerance);
    }
  }
}

TEST(MeshIo, OutputIsByteIdenticalForIdenticalInput) {
  TempDir dir;
  const Surface s = RandomizedSphere();
  const Eigen::MatrixX3d colors = RandomColors(s.NumVertices());
  for (const std::string ext : {"off", "obj", "ply"}) {
    SaveMesh(dir.File("a." + ext), s, &colors);
    SaveMesh(dir.File("b." + ext), s, &colors);
    EXPECT_EQ(ReadText(dir.File("a." + ext)), ReadText(dir.File("b." + ext))) << ext;
  }
}

TEST(MeshIo, WriterFormatIsStable) {
  TempDir dir;
  Surface s;
  s.V.resize(3, 3);
  s.V << 0, 0, 0, 1, 0, 0, 0.5, -0.25, 1e-20;
  s.F.resize(1, 3);
  s.F << 0, 1, 2;
  Eigen::MatrixX3d colors(3, 3);
  colors << 1, 0, 0, 0, 1, 0, 0, 0, 0.5;
  SaveMesh(dir.File("t.off"), s, &colors);
  EXPECT_EQ(ReadText(dir.File("t.off")),
            "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0.5 -0.25 1e-20 0 0 128 255\n"
            "3 0 1 2\n");
  SaveMesh(dir.File("t.obj"), s);
  EXPECT_EQ(ReadText(dir.File("t.obj")), "v 0 0 0\nv 1 0 0\nv 0.5 -0.25 1e-20\nf 1 2 3\n");
}

TEST(MeshIo, NonFiniteCoordinatesRoundTrip) {
  TempDir dir;
  Surface s = Icosphere(0);
  s.V(0, 0) = std::numeric_limits<double>::quiet_NaN();
  s.V(1, 2) = -std::numeric_limits<double>::infinity();
  for (const std::string ext : {"off", "obj", "ply"}) {
    SaveMesh(dir.File("n." + ext), s);
    const Surface r = LoadSurface(dir.File("n." + ext));
    EXPECT_TRUE(std::isnan(r.V(0, 0))) << ext;
    EXPECT_EQ(r.V(1, 2), -std::numeric_limits<double>::infinity()) << ext;
  }
}

TEST(MeshIo, OffVariantsCommentsAndPolygonFans) {
  TempDir dir;
  const std::string path = dir.File("v.OFF");  // extension matching ignores case
  WriteText(path,
            "# leading comment\n\nCNOFF\n# counts next\n5 2 0\n"
            "0 0 0  0 0 1  255 0 0 255\n1 0 0  0 0 1  0 255 0 255\n"
            "1 1 0  0 0 1  0 0 255 255 # trailing comment\n\n"
            "0 1 0  0 0 1  0.5 0.5 0.5 1.0\n2 2 2  0 0 1  0 0 0 255\n"
            "4 0 1 2 3\n3 1 4 2 255 255 255\n");
  Eigen::MatrixX3d colors;
  const Surface s = LoadSurface(path, &colors);
  ASSERT_EQ(s.NumVertices(), 5);
  EXPECT_EQ(s.V.row(2), Eigen::RowVector3d(1, 1, 0));
  ASSERT_EQ(s.NumFaces(), 3);  // the quad becomes the fan (0,1,2), (0,2,3)
  EXPECT_EQ(s.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(s.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(s.F.row(2), Eigen::RowVector3i(1, 4, 2));
  ASSERT_EQ(colors.rows(), 5);
  EXPECT_EQ(colors.row(1), Eigen::RowVector3d(0, 1, 0));    // integers are 0-255
  EXPECT_EQ(colors.row(3), Eigen::RowVector3d(.5, .5, .5));  // reals are 0-1
}

TEST(MeshIo, ObjStatementsFaceFormsAndNegativeIds) {
  TempDir dir;
  const std::string path = dir.File("m.obj");
  WriteText(path,
            "# exported\nmtllib m.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\n"
            "vt 0 0\nvn 0 0 1\ng group\nusemtl red\ns off\n"
            "f 1/1/1 2/1/1 3/1/1\nf -4//1 -2//1 -1//1\nf 2 3 4 1\n");
  const Surface s = LoadSurface(path);
  ASSERT_EQ(s.NumVertices(), 4);
  ASSERT_EQ(s.NumFaces(), 4);
  EXPECT_EQ(s.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(s.F.row(1), Eigen::RowVector3i(0, 2, 3));
  EXPECT_EQ(s.F.row(2), Eigen::RowVector3i(1, 2, 3));
  EXPECT_EQ(s.F.row(3), Eigen::RowVector3i(1, 3, 0));
}

TEST(MeshIo, ObjColorsOnlyWhenEveryVertexHasOne) {
  TempDir dir;
  WriteText(dir.File("c.obj"), "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
  Eigen::MatrixX3d colors;
  LoadSurface(dir.File("c.obj"), &colors);
  EXPECT_EQ(colors.rows(), 0);
}

// Binary PLY with extra vertex and face properties, an extra element and a fan polygon.
std::string BinaryPly(bool big_endian) {
  std::string h = std::string("ply\nformat ") +
                  (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\ncomment test\nelement vertex 4\nproperty float x\nproperty float y\n"
                  "property float z\nproperty uchar red\nproperty uchar green\n"
                  "property uchar blue\nproperty double quality\nelement face 2\n"
                  "property uchar flags\nproperty list uchar int vertex_indices\n"
                  "element edge 1\nproperty list ushort short ids\nend_header\n";
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0.1f, 1, 0}};
  for (int i = 0; i < 4; ++i) {
    for (float v : xyz[i]) Put(&h, v, big_endian);
    for (int k = 0; k < 3; ++k) Put<uint8_t>(&h, k == i % 3 ? 255 : 0, big_endian);
    Put<double>(&h, 0.5, big_endian);
  }
  Put<uint8_t>(&h, 9, big_endian);
  Put<uint8_t>(&h, 3, big_endian);
  for (int id : {0, 1, 2}) Put<int32_t>(&h, id, big_endian);
  Put<uint8_t>(&h, 9, big_endian);
  Put<uint8_t>(&h, 4, big_endian);
  for (int id : {3, 2, 1, 0}) Put<int32_t>(&h, id, big_endian);
  Put<uint16_t>(&h, 2, big_endian);
  Put<int16_t>(&h, 0, big_endian);
  Put<int16_t>(&h, 1, big_endian);
  return h;
}

TEST(MeshIo, BinaryPlyBothByteOrders) {
  TempDir dir;
  for (const bool big_endian : {false, true}) {
    const std::string path = dir.File(big_endian ? "be.ply" : "le.ply");
    WriteText(path, BinaryPly(big_endian));
    Eigen::MatrixX3d colors;
    const Surface s = LoadSurface(path, &colors);
    ASSERT_EQ(s.NumVertices(), 4);
    EXPECT_EQ(s.V(3, 0), static_cast<double>(0.1f));
    ASSERT_EQ(s.NumFaces(), 3);
    EXPECT_EQ(s.F.row(1), Eigen::RowVector3i(3, 2, 1));
    EXPECT_EQ(s.F.row(2), Eigen::RowVector3i(3, 1, 0));
    ASSERT_EQ(colors.rows(), 4);
    EXPECT_EQ(colors.row(1), Eigen::RowVector3d(0, 1, 0));
  }
}

TEST(MeshIo, AsciiPlyWithIntegerCoordinatesAndFloatColors) {
  TempDir dir;
  WriteText(dir.File("a.ply"),
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty int x\nproperty int y\n"
            "property int z\nproperty float red\nproperty float green\nproperty float blue\n"
            "element face 1\nproperty list uchar uint vertex_index\nend_header\n"
            "0 0 0 0.25 0 1\n2 0 0 0 0 0\n0 2 0 1 1 1\n3 0 1 2\n");
  Eigen::MatrixX3d colors;
  const Surface s = LoadSurface(dir.File("a.ply"), &colors);
  EXPECT_EQ(s.V.row(1), Eigen::RowVector3d(2, 0, 0));
  EXPECT_EQ(s.F.row(0), Eigen::RowVector3i(0, 1, 2));
  EXPECT_EQ(colors(0, 0), 0.25);
}

TEST(MeshIo, StlAsciiAndBinaryWeldVerticesInOrderOfAppearance) {
  TempDir dir;
  WriteText(dir.File("a.stl"),
            "solid square\nfacet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n"
            "  vertex 1 1 0\n endloop\nendfacet\nfacet normal 0 0 1\n outer loop\n"
            "  vertex 0 0 0\n  vertex 1 1 0\n  vertex 0 1 -0\n endloop\nendfacet\n"
            "endsolid square\n");
  // Binary, with a header that starts with "solid" as some exporters write.
  std::string bin = "solid but binary";
  bin.resize(80, ' ');
  Put<uint32_t>(&bin, 2);
  const float tri[2][3][3] = {{{0, 0, 0}, {1, 0, 0}, {1, 1, 0}},
                              {{0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
  for (const auto& t : tri) {
    for (int k = 0; k < 3; ++k) Put<float>(&bin, k == 2 ? 1.f : 0.f);
    for (const auto& p : t) {
      for (float v : p) Put<float>(&bin, v);
    }
    Put<uint16_t>(&bin, 0);
  }
  WriteText(dir.File("b.stl"), bin);
  for (const std::string name : {"a.stl", "b.stl"}) {
    const Surface s = LoadSurface(dir.File(name));
    ASSERT_EQ(s.NumVertices(), 4) << name;
    EXPECT_EQ(s.V.row(3), Eigen::RowVector3d(0, 1, 0)) << name;
    ASSERT_EQ(s.NumFaces(), 2) << name;
    EXPECT_EQ(s.F.row(0), Eigen::RowVector3i(0, 1, 2)) << name;
    EXPECT_EQ(s.F.row(1), Eigen::RowVector3i(0, 2, 3)) << name;
  }
}

TEST(MeshIo, DefectiveFacesAreKept) {
  // A duplicate face, a face that repeats a vertex and an unreferenced vertex must all survive
  // loading so that validation can report them.
  TempDir dir;
  WriteText(dir.File("d.off"), "OFF\n5 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n9 9 9\n"
                               "3 0 1 2\n3 2 1 0\n3 0 0 3\n3 0 2 3\n");
  const Surface s = LoadSurface(dir.File("d.off"));
  EXPECT_EQ(s.NumVertices(), 5);
  EXPECT_EQ(s.NumFaces(), 4);
  EXPECT_THROW(LoadMesh(dir.File("d.off")), InvalidInputError);
}

TEST(MeshIo, LoadMeshKeepsIdsOfAManifoldMesh) {
  TempDir dir;
  const Surface s = RandomizedSphere();
  SaveMesh(dir.File("s.off"), s);
  const TriMesh mesh = LoadMesh(dir.File("s.off"));
  const Surface back = ToSurface(mesh);
  EXPECT_EQ(back.V, s.V);
  EXPECT_EQ(back.F, s.F);
}

TEST(MeshIo, LoadMeshRejectsFacesTheHalfEdgeMeshCannotHold) {
  TempDir dir;
  // Three triangles on one edge: a non-manifold edge.
  WriteText(dir.File("nm.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\n"
                                "f 1 2 3\nf 2 1 4\nf 1 2 5\n");
  EXPECT_EQ(LoadSurface(dir.File("nm.obj")).NumFaces(), 3);
  try {
    LoadMesh(dir.File("nm.obj"));
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("nm.obj"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1 of 3 faces"), std::string::npos) << e.what();
  }
}

TEST(MeshIo, SaveRejectsBadInput) {
  TempDir dir;
  Surface s = Icosphere(0);
  Eigen::MatrixX3d colors = Eigen::MatrixX3d::Zero(3, 3);
  EXPECT_THROW(SaveMesh(dir.File("x.off"), s, &colors), InvalidInputError);
  EXPECT_THROW(SaveMesh(dir.File("x.stl"), s), InvalidInputError);
  EXPECT_THROW(SaveMesh(dir.File("missing/dir/x.off"), s), IoError);
  s.F(0, 0) = s.NumVertices();
  EXPECT_THROW(SaveMesh(dir.File("x.off"), s), InvalidInputError);
}

}  // namespace
}  // namespace symembed

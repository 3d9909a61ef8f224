// Broken mesh files: each is rejected as a whole with InvalidInputError (IoError when it cannot
// be read) whose message names the file, the line for text formats, and the problem.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include "core/errors.h"
#include "core/mesh_io.h"
#include "core/primitives.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::TempDir;
using testing::WriteText;

struct Case {
  const char* file;
  std::string content;
  const char* expected;  // substring of the message after the file name
};

const char kTetraVertices[] = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";

std::vector<Case> Cases() {
  const std::string v = kTetraVertices;
  const std::string ply_head = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n"
                               "property float y\nproperty float z\nelement face 1\n"
                               "property list uchar int vertex_indices\nend_header\n";
  const std::string ply_bin_head = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n"
                                   "property float x\nproperty float y\nproperty float z\n"
                                   "element face 1\nproperty list uchar int vertex_indices\n"
                                   "end_header\n";
  std::string stl_short_binary(84, '\0');
  stl_short_binary[80] = 5;  // declares 5 triangles, holds none
  return {
      {"empty.off", "", "empty file"},
      {"blank.off", "  \n# only a comment\n\n", "no OFF header"},
      {"header.off", "OFX\n4 1 0\n" + v + "3 0 1 2\n", ":1: expected an OFF header"},
      {"binary_header.off", "OFF BINARY\n", "binary OFF is not supported"},
      {"counts.off", "OFF\n4 x 0\n", ":2: expected an integer (face count), found 'x'"},
      {"negative_count.off", "OFF\n-4 1 0\n", ":2: invalid vertex count -4"},
      {"missing_counts.off", "OFF\n4 1\n", "truncated header: missing the edge count"},
      {"truncated_vertices.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n",
       "truncated: the file ends after 2 of 4 vertices"},
      {"truncated_faces.off", "OFF\n4 2 0\n" + v + "3 0 1 2\n",
       "truncated: the file ends after 1 of 2 faces"},
      {"truncated_face_line.off", "OFF\n4 1 0\n" + v + "3 0 1\n",
       ":7: face 0 declares 3 vertices but lists 2"},
      {"too_few_vertices_declared.off", "OFF\n3 1 0\n" + v + "3 0 1 2\n",
       ":6: face 0 has 0 vertices; a face needs at least 3 (does the header's vertex count 3 match?)"},
      {"too_many_vertices_declared.off", "OFF\n5 1 0\n" + v + "3 0 1 2\n",
       ":7: vertex 4 has 4 values, expected 3"},
      {"too_few_faces_declared.off", "OFF\n4 1 0\n" + v + "3 0 1 2\n3 0 2 3\n",
       ":8: unexpected data '3' after the 1 faces declared"},
      {"nonnumeric.off", "OFF\n4 1 0\n0 0 0\n1 abc 0\n0 1 0\n0 0 1\n3 0 1 2\n",
       ":4: expected a number (vertex 1), found 'abc'"},
      {"number_with_suffix.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1.5x 0\n0 0 1\n3 0 1 2\n",
       ":5: expected a number (vertex 2), found '1.5x'"},
      {"index_out_of_range.off", "OFF\n4 1 0\n" + v + "3 0 1 4\n",
       ":7: face 0: vertex id 4 out of range [0, 4)"},
      {"negative_index.off", "OFF\n4 1 0\n" + v + "3 0 -1 2\n", "vertex id -1 out of range"},
      {"float_index.off", "OFF\n4 1 0\n" + v + "3 0 1.0 2\n",
       "expected an integer vertex id (face 0), found '1.0'"},
      {"two_gon.off", "OFF\n4 1 0\n" + v + "2 0 1\n", "face 0 has 2 vertices; a face needs"},
      {"face_garbage.off", "OFF\n4 1 0\n" + v + "3 0 1 2 red\n", "unexpected token 'red'"},
      {"no_faces.off", "OFF\n4 0 0\n" + v, "the mesh has no faces"},
      {"no_vertices.off", "OFF\n0 0 0\n", "the mesh has no vertices"},
      {"huge_count.off", "OFF\n999999999 1 0\n0 0 0\n", "the file ends after 1 of 999999999"},
      {"unknown.obj", "v 0 0 0\nvx 1 0 0\n", ":2: unknown OBJ statement 'vx'"},
      {"short_vertex.obj", "v 0 0\n", ":1: vertex has 2 values"},
      {"nonnumeric.obj", "v 0 0 zero\n", ":1: expected a number (vertex coordinate), found 'zero'"},
      {"zero_index.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n", ":4: vertex id 0 in face"},
      {"out_of_range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n",
       ":4: vertex id 4 out of range [1, 3]"},
      {"relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n",
       ":4: relative vertex id '-4' points before the first vertex"},
      {"bad_face_token.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3x\n",
       ":4: expected a vertex id in face, found '3x'"},
      {"bad_face_suffix.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3/x\n",
       ":4: malformed face vertex '3/x'"},
      {"two_gon.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", ":3: face has 2 vertices"},
      {"no_faces.obj", "v 0 0 0\n", "the mesh has no faces"},
      {"only_comments.obj", "# nothing\n", "the mesh has no vertices"},
      {"magic.ply", "plx\n", ":1: not a PLY file"},
      {"no_end_header.ply", "ply\nformat ascii 1.0\nelement vertex 3\n",
       "truncated header: no 'end_header' line"},
      {"format.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n",
       ":2: unknown PLY format 'binary_middle_endian'"},
      {"type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float128 x\n",
       ":4: unknown property type 'float128'"},
      {"no_vertex.ply", "ply\nformat ascii 1.0\nelement face 0\nend_header\n",
       "no 'vertex' element"},
      {"no_x.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float y\n"
                   "element face 0\nproperty list uchar int vertex_indices\nend_header\n",
       "no scalar property 'x'"},
      {"truncated.ply", ply_head + "0 0 0\n1 0 0\n", "truncated: the data ends at 'vertex' 2"},
      {"nonnumeric.ply", ply_head + "0 0 0\n1 z 0\n0 1 0\n3 0 1 2\n",
       ":11: expected a number in 'vertex' 1, found 'z'"},
      {"extra_value.ply", ply_head + "0 0 0 7\n1 0 0\n0 1 0\n3 0 1 2\n",
       ":10: unexpected value '7' at the end of 'vertex' 0"},
      {"trailing.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 2\n",
       ":14: unexpected data '3' after the last element"},
      {"index.ply", ply_head + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
       "face 0: vertex id 3 out of range [0, 3)"},
      {"truncated_binary.ply", ply_bin_head + std::string(20, '\0'),
       "truncated binary data: element 'vertex' declares 3 records"},
      {"huge_list.ply", ply_bin_head + std::string(36, '\0') + "\xff",
       "truncated binary data at 'face' 0"},
      {"stl_binary_size.stl", stl_short_binary,
       "binary STL of 84 bytes declares 5 triangles, which need 334 bytes"},
      {"short.stl", "hello", "not an STL file"},
      {"no_endsolid.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                          "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\n",
       "truncated: missing 'endsolid'"},
      {"bad_keyword.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                          "vertex 1 0 0\nvertx 0 1 0\n",
       ":6: expected 'vertex', found 'vertx'"},
      {"unsupported.xyz", "0 0 0\n", "unsupported mesh file extension 'xyz'"},
  };
}

TEST(MeshIoMalformed, EachBrokenFileIsRejectedWithFileAndProblem) {
  TempDir dir;
  for (const Case& c : Cases()) {
    SCOPED_TRACE(c.file);
    const std::string path = dir.File(c.file);
    WriteText(path, c.content);
    try {
      LoadSurface(path);
      ADD_FAILURE() << "loaded without error";
    } catch (const InvalidInputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(path, 0), 0u) << message;  // starts with the path
      EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    }
  }
}

TEST(MeshIoMalformed, UnreadableFilesRaiseIoError) {
  TempDir dir;
  EXPECT_THROW(LoadSurface(dir.File("missing.off")), IoError);
  testing::WriteText(dir.File("d.off/inner"), "x");  // d.off is a directory
  EXPECT_THROW(LoadSurface(dir.File("d.off")), IoError);
}

TEST(MeshIoMalformed, BinaryGarbageIsRejectedInEveryFormat) {
  TempDir dir;
  std::mt19937 rng(3);
  for (const std::string ext : {"off", "obj", "ply", "stl"}) {
    for (int trial = 0; trial < 20; ++trial) {
      std::string garbage(1 + rng() % 4000, '\0');
      for (char& ch : garbage) ch = static_cast<char>(rng());
      const std::string path = dir.File("garbage." + ext);
      WriteText(path, garbage);
      try {
        LoadSurface(path);
        ADD_FAILURE() << ext << " garbage loaded";
      } catch (const InvalidInputError& e) {
        EXPECT_NE(std::string(e.what()).find("garbage." + ext), std::string::npos);
      }
    }
  }
}

// Every prefix and many single-byte corruptions of valid files either load or raise
// InvalidInputError: no crash, hang or other exception.
TEST(MeshIoMalformed, TruncationsAndCorruptionsNeverCrash) {
  TempDir dir;
  Surface s = Icosphere(1);
  Eigen::MatrixX3d colors = Eigen::MatrixX3d::Constant(s.NumVertices(), 3, 0.5);
  std::vector<std::pair<std::string, std::string>> files;
  for (const std::string ext : {"off", "obj", "ply"}) {
    SaveMesh(dir.File("ok." + ext), s, &colors);
    files.emplace_back(ext, testing::ReadText(dir.File("ok." + ext)));
  }
  std::string stl = std::string(80, ' ');
  const uint32_t n = s.NumFaces();
  stl.append(reinterpret_cast<const char*>(&n), 4);
  for (int f = 0; f < s.NumFaces(); ++f) {
    float rec[12] = {0, 0, 1};
    for (int k = 0; k < 9; ++k) rec[3 + k] = static_cast<float>(s.V(s.F(f, k / 3), k % 3));
    stl.append(reinterpret_cast<const char*>(rec), sizeof(rec));
    stl.append(2, '\0');
  }
  files.emplace_back("stl", stl);
  std::mt19937 rng(5);
  int loaded = 0, rejected = 0;
  for (const auto& [ext, text] : files) {
    std::vector<std::string> variants;
    for (size_t len = 0; len < text.size(); len += 1 + text.size() / 300) {
      variants.push_back(text.substr(0, len));
    }
    for (int trial = 0; trial < 300; ++trial) {
      std::string corrupt = text;
      corrupt[rng() % corrupt.size()] = static_cast<char>(rng());
      variants.push_back(corrupt);
    }
    for (const std::string& data : variants) {
      try {
        const Surface r = ParseMesh(data, ext, "variant." + ext);
        ASSERT_GT(r.NumFaces(), 0);
        ASSERT_GE(r.F.minCoeff(), 0);
        ASSERT_LT(r.F.maxCoeff(), r.NumVertices());
        ++loaded;
      } catch (const InvalidInputError&) {
        ++rejected;
      }
    }
  }
  EXPECT_GT(rejected, 0);
  EXPECT_GT(loaded, 0);
}

}  // namespace
}  // namespace symembed

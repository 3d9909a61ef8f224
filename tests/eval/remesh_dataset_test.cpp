#include "eval/synthetic/remesh_dataset.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <vector>

#include "core/errors.h"
#include "core/mesh_io.h"
#include "eval/datasets/pairs_vts.h"
#include "eval/synthetic/random.h"
#include "eval/synthetic/synthetic.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

namespace fs = std::filesystem;

// A small pairs_vts dataset with direct and mirrored ground truth on every vertex.
std::string WriteInput(const testing::TempDir& dir) {
  SynthOptions o;
  o.kinds = {FigureKind::kQuadruped};
  o.poses = 3;
  o.vertices = 1200;
  WriteSyntheticDataset(dir.File("in"), o);
  return dir.File("in");
}

// One shape of the input and of its remeshed copy, with their ground truth.
struct ShapeBeforeAfter {
  std::string name;
  Surface a, b;
  ShapeGroundTruth ga, gb;
};

// Every shape of the dataset under `in` beside its copy under `out`; the pair lists must agree.
std::vector<ShapeBeforeAfter> ReadBeforeAfter(const std::string& in, const std::string& out) {
  const PairsVtsDataset input(PairsVtsOptions{in, {}});
  const PairsVtsDataset output(PairsVtsOptions{out, {}});
  const DatasetIndex before = input.Load(), after = output.Load();
  EXPECT_EQ(after.pairs.size(), before.pairs.size());
  for (size_t p = 0; p < before.pairs.size() && p < after.pairs.size(); ++p) {
    EXPECT_EQ(after.pairs[p].source, before.pairs[p].source);
    EXPECT_EQ(after.pairs[p].target, before.pairs[p].target);
  }
  std::vector<ShapeBeforeAfter> shapes;
  for (const DatasetShape& shape : before.shapes) {
    const DatasetShape* copy = after.Find(shape.name);
    EXPECT_NE(copy, nullptr) << shape.name;
    if (!copy) continue;
    ShapeBeforeAfter s{
        shape.name, LoadSurface(shape.mesh_path), LoadSurface(copy->mesh_path), {}, {}};
    s.ga = input.GroundTruth(shape, s.a.NumVertices());
    s.gb = output.GroundTruth(*copy, s.b.NumVertices());
    EXPECT_EQ(s.gb.ids.size(), s.ga.ids.size()) << shape.name;
    EXPECT_EQ(s.gb.sym_ids.size(), s.ga.sym_ids.size()) << shape.name;
    shapes.push_back(std::move(s));
  }
  return shapes;
}

TEST(RemeshDataset, KeptVerticesKeepTheirPositionsAndGroundTruthLines) {
  testing::TempDir dir;
  const std::string in = WriteInput(dir);
  RemeshDatasetOptions options;
  options.vertices = 500;
  options.anisotropy = 4.0;
  const RemeshDatasetSummary summary = WriteRemeshedDataset(in, dir.File("out"), options);
  EXPECT_EQ(summary.shapes, 3);
  EXPECT_EQ(summary.remeshed, 3);
  EXPECT_EQ(summary.pairs, 3);

  const std::vector<ShapeBeforeAfter> shapes = ReadBeforeAfter(in, dir.File("out"));
  ASSERT_EQ(shapes.size(), 3u);
  for (const auto& [name, a, b, ga, gb] : shapes) {
    EXPECT_LE(b.NumVertices(), 520);
    EXPECT_GE(b.NumVertices(), 500);
    int kept = 0;
    for (size_t line = 0; line < ga.ids.size(); ++line) {
      // A kept line names the vertex at the same place; every vertex of the output is named.
      if (gb.ids[line] >= 0) {
        ASSERT_GE(ga.ids[line], 0);
        ASSERT_EQ(b.V.row(gb.ids[line]), a.V.row(ga.ids[line])) << name << " line " << line;
        ++kept;
      }
      if (gb.sym_ids[line] >= 0) {
        ASSERT_EQ(b.V.row(gb.sym_ids[line]), a.V.row(ga.sym_ids[line]));
      }
    }
    EXPECT_EQ(kept, b.NumVertices()) << name;
  }
  const std::string readme = testing::ReadText(dir.File("out/README.md"));
  EXPECT_NE(readme.find("4 times longer"), std::string::npos) << readme;
}

// Denser than the input: subdivided, then decimated to more vertices than the input has. The
// ground truth names the old vertices, moved by a fraction of an edge; the new ones are unnamed.
TEST(RemeshDataset, SubdivisionRemeshesDenserWithTheGroundTruthOnTheOldVertices) {
  testing::TempDir dir;
  const std::string in = WriteInput(dir);
  RemeshDatasetOptions options;
  options.vertices = 2500;
  options.subdivide = 1;
  const RemeshDatasetSummary summary = WriteRemeshedDataset(in, dir.File("out"), options);
  EXPECT_EQ(summary.remeshed, 3);
  const std::vector<ShapeBeforeAfter> shapes = ReadBeforeAfter(in, dir.File("out"));
  ASSERT_EQ(shapes.size(), 3u);
  for (const auto& [name, a, b, ga, gb] : shapes) {
    EXPECT_GE(b.NumVertices(), 2500);
    EXPECT_LE(b.NumVertices(), 2520);
    const double edge = MeanEdgeLength(a);
    int kept = 0;
    double moved = 0.0;
    for (size_t line = 0; line < ga.ids.size(); ++line) {
      if (gb.ids[line] < 0) continue;
      const double d = (b.V.row(gb.ids[line]) - a.V.row(ga.ids[line])).norm();
      ASSERT_LT(d, 2.0 * edge) << line;  // a few vertices move more than the mean edge
      moved += d;
      ++kept;
    }
    EXPECT_LT(moved / kept, 0.25 * edge) << name;
    // About 2,500 of the ~4,800 subdivided vertices survive, old and new alike.
    EXPECT_GT(kept, a.NumVertices() / 4) << name;
    EXPECT_LT(kept, b.NumVertices() * 3 / 4) << name;
  }
  EXPECT_NE(testing::ReadText(dir.File("out/README.md")).find("Loop subdivision"),
            std::string::npos);
  options.subdivide = 3;
  EXPECT_THROW(WriteRemeshedDataset(in, dir.File("out3"), options), ConfigError);
}

TEST(RemeshDataset, SameOptionsGiveTheSameFilesAndEachShapeItsOwnDirection) {
  testing::TempDir dir;
  const std::string in = WriteInput(dir);
  RemeshDatasetOptions options;
  options.vertices = 300;
  WriteRemeshedDataset(in, dir.File("iso"), options);
  WriteRemeshedDataset(in, dir.File("iso_again"), options);
  options.anisotropy = 4.0;
  WriteRemeshedDataset(in, dir.File("aniso"), options);
  // Shape i's direction comes from its own stream (remesh_dataset.h): its edges along it are
  // shorter than the isotropic remeshing's.
  const std::vector<std::string> names = {"quadruped0", "quadruped1", "quadruped2"};
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string mesh = "/shapes/" + names[i] + ".off";
    EXPECT_EQ(testing::ReadText(dir.File("iso") + mesh),
              testing::ReadText(dir.File("iso_again") + mesh));
    const Eigen::Vector3d d = RandomUnitVector(DeriveSeed(options.seed, "remesh_direction", i));
    const double iso = testing::EdgeExtentRatio(LoadSurface(dir.File("iso") + mesh), d);
    const double aniso = testing::EdgeExtentRatio(LoadSurface(dir.File("aniso") + mesh), d);
    EXPECT_LT(aniso, 0.9 * iso) << names[i] << ": " << iso << " " << aniso;
  }
}

TEST(RemeshDataset, BadInputNamesTheFile) {
  testing::TempDir dir;
  RemeshDatasetOptions options;
  EXPECT_THROW(WriteRemeshedDataset(dir.File("missing"), dir.File("out"), options), IoError);
  options.vertices = 10;
  EXPECT_THROW(WriteRemeshedDataset(dir.File("missing"), dir.File("out"), options), ConfigError);
  // A ground-truth file with an id out of range.
  const std::string in = WriteInput(dir);
  testing::WriteText(in + "/corres/quadruped1.vts", "1\n99999\n");
  options = RemeshDatasetOptions();
  options.vertices = 500;
  try {
    WriteRemeshedDataset(in, dir.File("out2"), options);
    FAIL() << "no error";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("quadruped1.vts"), std::string::npos) << e.what();
  }
}

TEST(RemeshDataset, CommandWritesADatasetAndRejectsBadArguments) {
  testing::TempDir dir;
  const std::string in = WriteInput(dir);
  const std::string bin = SYMEMBED_BINARY;
  std::string out;
  ASSERT_EQ(testing::RunShell(bin + " remesh --in " + in + " --out " + dir.File("r") +
                                  " --vertices 600 --anisotropy 3 --subdivide 1",
                              &out),
            0)
      << out;
  EXPECT_NE(out.find("wrote 3 shapes (3 remeshed) and 3 pairs"), std::string::npos) << out;
  EXPECT_TRUE(fs::exists(dir.File("r/corres/quadruped2.sym.vts")));
  EXPECT_EQ(testing::RunShell(bin + " remesh --in " + in + " --out " + dir.File("r"), &out), 1);
  EXPECT_NE(out.find("--force"), std::string::npos) << out;
  EXPECT_EQ(
      testing::RunShell(bin + " remesh --in " + in + " --out " + dir.File("r") + " --force", &out),
      0)
      << out;
  EXPECT_EQ(testing::RunShell(
                bin + " remesh --in " + in + " --out " + dir.File("s") + " --anisotropy x", &out),
            2);
  EXPECT_NE(out.find("--anisotropy"), std::string::npos) << out;
  EXPECT_EQ(testing::RunShell(bin + " remesh --in " + in + " --out " + in + " --force", &out), 2);
  EXPECT_NE(out.find("must not be the input"), std::string::npos) << out;
  EXPECT_TRUE(fs::exists(in + "/shapes/quadruped0.off"));
  EXPECT_EQ(testing::RunShell(bin + " remesh --out " + dir.File("s"), &out), 2);
  EXPECT_NE(out.find("--in"), std::string::npos) << out;
}

}  // namespace
}  // namespace symembed

#include "eval/synthetic/remesh_dataset.h"

#include <gtest/gtest.h>

#include <filesystem>

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

  const PairsVtsDataset input(PairsVtsOptions{in, {}});
  const PairsVtsDataset output(PairsVtsOptions{dir.File("out"), {}});
  const DatasetIndex before = input.Load(), after = output.Load();
  ASSERT_EQ(after.pairs.size(), before.pairs.size());
  for (size_t p = 0; p < before.pairs.size(); ++p) {
    EXPECT_EQ(after.pairs[p].source, before.pairs[p].source);
    EXPECT_EQ(after.pairs[p].target, before.pairs[p].target);
  }
  for (const DatasetShape& shape : before.shapes) {
    const DatasetShape* out = after.Find(shape.name);
    ASSERT_NE(out, nullptr) << shape.name;
    const Surface a = LoadSurface(shape.mesh_path), b = LoadSurface(out->mesh_path);
    EXPECT_LE(b.NumVertices(), 520);
    EXPECT_GE(b.NumVertices(), 500);
    const ShapeGroundTruth ga = input.GroundTruth(shape, a.NumVertices());
    const ShapeGroundTruth gb = output.GroundTruth(*out, b.NumVertices());
    ASSERT_EQ(gb.ids.size(), ga.ids.size());
    ASSERT_EQ(gb.sym_ids.size(), ga.sym_ids.size());
    int kept = 0;
    for (size_t line = 0; line < ga.ids.size(); ++line) {
      // A kept line names the vertex at the same place; every vertex of the output is named.
      if (gb.ids[line] >= 0) {
        ASSERT_GE(ga.ids[line], 0);
        ASSERT_EQ(b.V.row(gb.ids[line]), a.V.row(ga.ids[line])) << shape.name << " line " << line;
        ++kept;
      }
      if (gb.sym_ids[line] >= 0) {
        ASSERT_EQ(b.V.row(gb.sym_ids[line]), a.V.row(ga.sym_ids[line]));
      }
    }
    EXPECT_EQ(kept, b.NumVertices()) << shape.name;
  }
  const std::string readme = testing::ReadText(dir.File("out/README.md"));
  EXPECT_NE(readme.find("4 times longer"), std::string::npos) << readme;
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
                                  " --vertices 600 --anisotropy 3",
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

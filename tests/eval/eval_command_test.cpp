// `symembed eval` end to end on a small pairs_vts dataset written by the test.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "core/mesh_io.h"
#include "core/primitives.h"
#include "eval/json.h"
#include "core/map_io.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

constexpr int kN = 6;  // 6 x 6 grids

int Mirror(int v) { return (v / kN) * kN + (kN - 1 - v % kN); }

// shapes a, b, c (same grid), identity ground truth, mirror as symmetric ground truth.
void WriteDataset(const std::string& root) {
  std::string vts, sym;
  for (int v = 0; v < kN * kN; ++v) {
    vts += std::to_string(v + 1) + "\n";
    sym += std::to_string(Mirror(v) + 1) + "\n";
  }
  std::filesystem::create_directories(root + "/shapes");
  for (const char* name : {"a", "b", "c"}) {
    SaveMesh(root + "/shapes/" + name + ".off", GridMesh(kN, kN, 2.0, 2.0));
    testing::WriteText(root + "/corres/" + name + ".vts", vts);
    testing::WriteText(root + "/corres/" + name + ".sym.vts", sym);
  }
  testing::WriteText(root + "/test_pairs.txt", "a\tb\na\tc\nb\tc\n\n");
}

// The dataset above in a temporary folder (dir_.File("data")).
class EvalCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    Registry registry;
    RegisterBuiltinStages(registry);
    if (!registry.Has("dataset", "pairs_vts") || !registry.Has("geodesics", "dijkstra")) {
      GTEST_SKIP() << "needs the pairs_vts loader and the dijkstra stage";
    }
    WriteDataset(dir.File("data"));
  }
  testing::TempDir dir;
};

TEST_F(EvalCommand, ScoresMapsRecordsMalformedOnesAndWritesOutputs) {
  std::vector<int> identity(kN * kN), mirror(kN * kN);
  for (int v = 0; v < kN * kN; ++v) {
    identity[v] = v;
    mirror[v] = Mirror(v);
  }
  WriteMapFile(dir.File("maps/a_b.map"), identity);
  testing::WriteText(dir.File("maps/a_c.map"), "1\n2\n3\n");  // wrong length
  WriteMapFile(dir.File("maps/b_c.map"), mirror);
  std::string out;
  const int code = testing::Symembed("eval --dataset " + dir.File("data") + " --maps " +
                                         dir.File("maps") +
                                         " --base 1 --name grid --geodesics dijkstra --out " +
                                         dir.File("out"),
                                     &out);
  EXPECT_EQ(code, 1) << out;  // one pair failed: reported, not fatal
  EXPECT_NE(out.find("a -> c"), std::string::npos) << out;
  const std::string pairs = testing::ReadText(dir.File("out/pairs.csv"));
  EXPECT_NE(pairs.find("a,b,ok,36,0,0,0,100,100,100,"), std::string::npos) << pairs;
  EXPECT_NE(pairs.find("a,c,failed"), std::string::npos) << pairs;
  EXPECT_NE(pairs.find("3 entries, expected 36"), std::string::npos) << pairs;
  EXPECT_NE(pairs.find(",left_right,"), std::string::npos) << pairs;
  const JsonValue summary = ParseJson(testing::ReadText(dir.File("out/summary.json")));
  EXPECT_EQ(summary.Get("pairs").AsNumber(), 3);
  EXPECT_EQ(summary.Get("failed_pairs").AsNumber(), 1);
  EXPECT_EQ(summary.Get("flipped_pairs").Get("left_right").AsNumber(), 1);
  EXPECT_EQ(summary.Get("evaluation_geodesics").AsString(), "dijkstra");
  EXPECT_EQ(summary.Get("mean_flip_tolerant").AsNumber(), 0.0);
  EXPECT_FALSE(testing::ReadText(dir.File("out/curve.csv")).empty());
  EXPECT_FALSE(testing::ReadText(dir.File("out/timings.csv")).empty());

  // Usage errors exit 2.
  EXPECT_EQ(testing::Symembed("eval --maps x", &out), 2) << out;
}

// Maps that are plainly 1-based scored with --base 0 are called out; --out alone names the
// evaluation; a folder where a map file should be is called a folder.
TEST_F(EvalCommand, WrongBaseAFolderForAMapAndNameFromOut) {
  std::string text;  // the identity, 1-based
  for (int v = 0; v < kN * kN; ++v) text += std::to_string(v + 1) + "\n";
  testing::WriteText(dir.File("maps/a_b.map"), text);
  // 1-based too, but without the last id: it reads under --base 0, shifted.
  std::string without_last;
  for (int v = 0; v < kN * kN; ++v) {
    without_last += std::to_string(std::min(v + 1, kN * kN - 1)) + "\n";
  }
  testing::WriteText(dir.File("maps/b_c.map"), without_last);
  std::filesystem::create_directories(dir.File("maps/a_c.map"));
  std::string out;
  const int code = testing::Symembed("eval --dataset " + dir.File("data") + " --maps " +
                                         dir.File("maps") + " --base 0 --geodesics dijkstra --out " +
                                         dir.File("out/named"),
                                     &out);
  EXPECT_EQ(code, 1) << out;
  EXPECT_NE(out.find("the file looks 1-based (--base 1)"), std::string::npos) << out;
  EXPECT_NE(out.find("maps/a_c.map: is a folder, not a map file"), std::string::npos) << out;
  EXPECT_NE(out.find("none of the 1 maps uses target id 0"), std::string::npos) << out;
  EXPECT_NE(out.find("eval named:"), std::string::npos) << out;
  const JsonValue summary = ParseJson(testing::ReadText(dir.File("out/named/summary.json")));
  EXPECT_EQ(summary.Get("variant").AsString(), "named");
}

}  // namespace
}  // namespace symembed

// scripts/mirror-truth: the left-right ground truth of a dataset whose shapes share a template,
// from one reference shape's mirror plane.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "tests/test_util.h"

namespace symembed {
namespace {

std::string Script() { return "python3 " + testing::SourceDir() + "/scripts/mirror-truth "; }

// A box [0, 1] x [0, 2] x [-1, 1], its vertex at corner (x, y, z) listed at position
// order[x * 4 + y * 2 + (z > 0)]: the same surface under another vertex numbering per order.
std::string BoxOff(const std::vector<int>& order) {
  std::vector<std::string> rows(8);
  for (int c = 0; c < 8; ++c) {
    std::ostringstream row;
    row << (c >> 2 & 1) << " " << 2 * (c >> 1 & 1) << " " << ((c & 1) ? 1 : -1) << "\n";
    rows[order[c]] = row.str();
  }
  const int faces[12][3] = {{0, 1, 3}, {0, 3, 2}, {4, 6, 7}, {4, 7, 5}, {0, 4, 5}, {0, 5, 1},
                            {2, 3, 7}, {2, 7, 6}, {0, 2, 6}, {0, 6, 4}, {1, 5, 7}, {1, 7, 3}};
  std::string off = "OFF\n8 12 0\n";
  for (const std::string& r : rows) off += r;
  for (const auto& f : faces) {
    off += "3 " + std::to_string(order[f[0]]) + " " + std::to_string(order[f[1]]) + " " +
           std::to_string(order[f[2]]) + "\n";
  }
  return off;
}

// The template: its lines list the corners in the order 0, 3, 5, 6, 1, 2, 4, 7; a shape's .vts
// gives each line its own 1-based vertex id.
const std::vector<int> kLineCorners = {0, 3, 5, 6, 1, 2, 4, 7};

std::string Vts(const std::vector<int>& order, const std::vector<int>& corners) {
  std::string text;
  for (int c : corners) text += std::to_string(order[c] + 1) + "\n";
  return text;
}

// The mirror across z = 0 swaps corners c and c ^ 1: line i's partner lists corner
// kLineCorners[i] ^ 1.
std::vector<int> MirroredCorners() {
  std::vector<int> out;
  for (int c : kLineCorners) out.push_back(c ^ 1);
  return out;
}

TEST(MirrorTruth, WritesEachShapesLinesInTheReferencesMirrorOrder) {
  testing::TempDir dir;
  const std::vector<int> ref = {0, 1, 2, 3, 4, 5, 6, 7}, other = {5, 2, 7, 0, 6, 1, 3, 4};
  const std::string data = dir.File("set");
  testing::WriteText(data + "/shapes/ref.off", BoxOff(ref));
  testing::WriteText(data + "/shapes/other.off", BoxOff(other));
  testing::WriteText(data + "/corres/ref.vts", Vts(ref, kLineCorners));
  testing::WriteText(data + "/corres/other.vts", Vts(other, kLineCorners));
  testing::WriteText(data + "/corres/kept.vts", Vts(ref, kLineCorners));
  testing::WriteText(data + "/shapes/kept.off", BoxOff(ref));
  testing::WriteText(data + "/corres/kept.sym.vts", "9\n");  // linked as it is
  testing::WriteText(data + "/test_pairs.txt", "ref\tother\n\n");
  std::string out;
  ASSERT_EQ(
      testing::RunShell(Script() + "--reference ref " + data + " " + dir.File("out/set"), &out), 0)
      << out;
  EXPECT_NE(out.find("8 lines, mean distance 0.0000 of sqrt(area), involution on 1.000"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("2 .sym.vts written, 1 already there"), std::string::npos) << out;
  EXPECT_EQ(testing::ReadText(dir.File("out/set/corres/ref.sym.vts")), Vts(ref, MirroredCorners()));
  EXPECT_EQ(testing::ReadText(dir.File("out/set/corres/other.sym.vts")),
            Vts(other, MirroredCorners()));
  EXPECT_EQ(testing::ReadText(dir.File("out/set/corres/kept.sym.vts")), "9\n");
  EXPECT_EQ(testing::ReadText(dir.File("out/set/corres/other.vts")), Vts(other, kLineCorners));
  EXPECT_EQ(testing::ReadText(dir.File("out/set/test_pairs.txt")), "ref\tother\n\n");
  EXPECT_EQ(testing::ReadText(dir.File("out/set/shapes/other.off")), BoxOff(other));
}

TEST(MirrorTruth, NamesTheFileThatIsMissingOrDoesNotFit) {
  testing::TempDir dir;
  const std::vector<int> ref = {0, 1, 2, 3, 4, 5, 6, 7};
  const std::string data = dir.File("set");
  testing::WriteText(data + "/shapes/ref.off", BoxOff(ref));
  testing::WriteText(data + "/corres/ref.vts", Vts(ref, kLineCorners));
  std::string out;
  EXPECT_EQ(testing::RunShell(Script() + "--reference nope " + data + " " + dir.File("o1"), &out),
            1);
  EXPECT_NE(out.find(data + "/shapes/nope.off: cannot read"), std::string::npos) << out;

  testing::WriteText(data + "/shapes/short.off", BoxOff(ref));
  testing::WriteText(data + "/corres/short.vts", "1\n2\n");
  EXPECT_EQ(testing::RunShell(Script() + "--reference ref " + data + " " + dir.File("o2"), &out),
            1);
  EXPECT_NE(out.find(data + "/corres/short.vts: 2 lines, the reference has 8"), std::string::npos)
      << out;

  testing::WriteText(data + "/corres/ref.vts", "1\n99\n");
  EXPECT_EQ(testing::RunShell(Script() + "--reference ref " + data + " " + dir.File("o3"), &out),
            1);
  EXPECT_NE(out.find("ref.vts: line 2: '99' is not a vertex id 1..8"), std::string::npos) << out;

  EXPECT_EQ(testing::RunShell(Script() + data + " " + dir.File("o4"), &out), 2);
}

}  // namespace
}  // namespace symembed

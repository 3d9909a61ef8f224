#include "eval/datasets/shrec16.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>

#include "core/errors.h"
#include "registry/registry.h"
#include "tests/eval/dataset_test_util.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::TempDir;
using testing::WriteText;

const auto Create = testing::CreateDataset;
using testing::ExpectError;
using testing::Tetrahedron;

// The SHREC'16 partial layout: null shapes cat (tetrahedron, 4 vertices) and dog (5 vertices);
// cat partial shapes 2 and 10 (4 vertices each, so the natural order differs from the
// lexicographic one), one dog partial shape; the benchmark's number format.
void WritePartialTree(const std::string& root) {
  WriteText(root + "/null/cat.off", Tetrahedron());
  WriteText(root + "/null/dog.off", Tetrahedron(1));
  WriteText(root + "/cuts/cuts_cat_shape_10.off", Tetrahedron());
  WriteText(root + "/cuts/cuts_cat_shape_10.baryc_gt",
            "   1.0000000e+00   0.1 0.7 0.2\n"      // face 0 = (0 2 1): weight 0.7 -> vertex 2
            "   4.0000000e+00   0.6 0.2 0.2\n"      // face 3 = (1 2 3) -> vertex 1
            "   2.0000000e+00   0.0 0.0 1.0\n"      // face 1 = (0 1 3) -> vertex 3
            "   3.0000000e+00   0.2 0.5 0.3\n\n");  // face 2 = (0 3 2) -> vertex 3
  WriteText(root + "/cuts/cuts_cat_shape_10.baryc_gt_sym",
            "1 1 0 0\n1 0 1 0\n1 0 0 1\n4 0 0 1\n");  // vertices 0 2 1 3
  WriteText(root + "/cuts/cuts_cat_shape_2.off", Tetrahedron());
  WriteText(root + "/cuts/cuts_cat_shape_2.baryc_gt", "1 1 0 0\n1 1 0 0\n1 1 0 0\n1 1 0 0\n");
  WriteText(root + "/cuts/cuts_dog_shape_1.off", Tetrahedron());
  WriteText(root + "/cuts/cuts_dog_shape_1.baryc_gt", "1 1 0 0\n1 1 0 0\n1 1 0 0\n1 1 0 0\n");
}

TEST(Shrec16Partial, EachPartialShapeOntoItsClassNullShapeInNaturalOrder) {
  TempDir dir;
  WritePartialTree(dir.path());
  auto dataset = Create("{type: shrec16_partial, root: " + dir.path() + "}");
  const DatasetIndex index = dataset->Load();
  ASSERT_EQ(index.pairs.size(), 3u);
  EXPECT_EQ(index.pairs[0].source, "cuts_cat_shape_2");
  EXPECT_EQ(index.pairs[0].target, "cat");
  EXPECT_EQ(index.pairs[1].source, "cuts_cat_shape_10");
  EXPECT_EQ(index.pairs[1].target, "cat");
  EXPECT_EQ(index.pairs[2].source, "cuts_dog_shape_1");
  EXPECT_EQ(index.pairs[2].target, "dog");
  // The null shapes are one shape each, however many pairs name them.
  ASSERT_EQ(index.shapes.size(), 5u);
  int cats = 0;
  for (const auto& s : index.shapes) cats += s.name == "cat";
  EXPECT_EQ(cats, 1);
  EXPECT_EQ(index.Find("cat")->mesh_path, dir.path() + "/null/cat.off");
  EXPECT_EQ(index.Find("cuts_cat_shape_10")->class_name, "cat");
}

TEST(Shrec16Partial, GroundTruthIsTheLargestWeightVertexOfTheNullTriangle) {
  TempDir dir;
  WritePartialTree(dir.path());
  auto dataset = Create("{type: shrec16_partial, root: " + dir.path() + ", track: cuts}");
  const DatasetIndex index = dataset->Load();
  const ShapeGroundTruth partial = dataset->GroundTruth(*index.Find("cuts_cat_shape_10"), 4);
  const ShapeGroundTruth null_shape = dataset->GroundTruth(*index.Find("cat"), 4);
  EXPECT_EQ(partial.onto, "cat");
  EXPECT_TRUE(partial.ids.empty());
  EXPECT_TRUE(null_shape.ids.empty());
  const InputGroundTruth pair = PairGroundTruth(partial, "cuts_cat_shape_10", null_shape, "cat");
  EXPECT_EQ(pair.source_ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_EQ(pair.target_ids, (std::vector<int>{2, 1, 3, 3}));
  EXPECT_EQ(pair.target_sym_ids, (std::vector<int>{0, 2, 1, 3}));
  // Reversed (null onto partial): the same lines, sides swapped, no symmetric truth.
  const InputGroundTruth reversed =
      PairGroundTruth(null_shape, "cat", partial, "cuts_cat_shape_10");
  EXPECT_EQ(reversed.source_ids, (std::vector<int>{2, 1, 3, 3}));
  EXPECT_EQ(reversed.target_ids, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_TRUE(reversed.target_sym_ids.empty());
  // Onto another shape: no common ground truth.
  EXPECT_TRUE(PairGroundTruth(partial, "cuts_cat_shape_10", null_shape, "dog").source_ids.empty());
  // Without a _sym file, no symmetric truth.
  const ShapeGroundTruth two = dataset->GroundTruth(*index.Find("cuts_cat_shape_2"), 4);
  EXPECT_TRUE(two.onto_lines.target_sym_ids.empty());
  EXPECT_EQ(two.onto_lines.target_ids, (std::vector<int>{0, 0, 0, 0}));
}

TEST(Shrec16Partial, RestrictionsSelectClassesAndPairs) {
  TempDir dir;
  WritePartialTree(dir.path());
  WriteText(dir.path() + "/pairs.txt", "cuts_dog_shape_1 dog\n");
  auto dogs = Create("{type: shrec16_partial, root: " + dir.path() + ", classes: [dog]}")->Load();
  ASSERT_EQ(dogs.pairs.size(), 1u);
  EXPECT_EQ(dogs.shapes.size(), 2u);
  auto first = Create("{type: shrec16_partial, root: " + dir.path() + ", max_pairs: 1}")->Load();
  ASSERT_EQ(first.pairs.size(), 1u);
  EXPECT_EQ(first.pairs[0].source, "cuts_cat_shape_2");
  auto listed =
      Create("{type: shrec16_partial, root: " + dir.path() + ", pairs_file: pairs.txt}")->Load();
  ASSERT_EQ(listed.pairs.size(), 1u);
  EXPECT_EQ(listed.pairs[0].target, "dog");
}

TEST(Shrec16Partial, RejectsMalformedInputNamingFileAndLine) {
  auto load = [](const std::string& root, const std::string& extra = "") {
    return [root, extra] { Create("{type: shrec16_partial, root: " + root + extra + "}")->Load(); };
  };
  auto truth = [](const std::string& root, const std::string& shape, int n) {
    return [root, shape, n] {
      auto d = Create("{type: shrec16_partial, root: " + root + "}");
      const DatasetIndex index = d->Load();
      d->GroundTruth(*index.Find(shape), n);
    };
  };
  {
    TempDir dir;
    WritePartialTree(dir.path());
    WriteText(dir.path() + "/holes/holes_cat_shape_1.off", Tetrahedron());
    ExpectError<InvalidInputError>(load(dir.path()), {"both cuts/ and holes/", "track"});
    ExpectError<ConfigError>(load(dir.path(), ", track: slices"), {"track", "slices"});
  }
  {
    TempDir dir;
    WritePartialTree(dir.path());
    WriteText(dir.path() + "/cuts/cuts_horse_shape_1.off", Tetrahedron());
    ExpectError<InvalidInputError>(load(dir.path()), {"cuts_horse_shape_1.off", "no null shape"});
  }
  {
    TempDir dir;
    WritePartialTree(dir.path());
    WriteText(dir.path() + "/cuts/cat_1.off", Tetrahedron());
    ExpectError<InvalidInputError>(load(dir.path()), {"cat_1.off", "cuts_CLASS_shape_N"});
  }
  {
    TempDir dir;
    WritePartialTree(dir.path());
    std::filesystem::remove(dir.path() + "/cuts/cuts_dog_shape_1.baryc_gt");
    ExpectError<InvalidInputError>(load(dir.path()), {"cuts_dog_shape_1.baryc_gt", "missing"});
  }
  const std::vector<std::pair<std::string, std::vector<std::string>>> bad_rows = {
      {"1 1 0 0\n1 1 0 0\n1 1 0 0\n", {"3 rows", "4 vertices"}},
      {"1 1 0 0\n5 1 0 0\n1 1 0 0\n1 1 0 0\n", {":2:", "triangle 5 out of range [1, 4]"}},
      {"1 1 0 0\n1 1 0 0\n1.5 1 0 0\n1 1 0 0\n", {":3:", "not an integer"}},
      {"1 1 0 0\n1 1 0 0\n1 1 0 0\n1 -1 2 0\n", {":4:", "weight '-1'"}},
      {"1 1 0 0\n1 1 0\n1 1 0 0\n1 1 0 0\n", {":2:", "3 fields"}},
      {"1 1 0 0\n\n1 1 0 0\n1 1 0 0\n", {":2:", "blank line"}},
      {"1 1 0 0\n1 nan 0 0\n1 1 0 0\n1 1 0 0\n", {":2:", "weight 'nan'"}},
  };
  for (const auto& [text, fragments] : bad_rows) {
    TempDir dir;
    WritePartialTree(dir.path());
    WriteText(dir.path() + "/cuts/cuts_dog_shape_1.baryc_gt", text);
    std::vector<std::string> expected = fragments;
    expected.push_back("cuts_dog_shape_1.baryc_gt");
    ExpectError<InvalidInputError>(truth(dir.path(), "cuts_dog_shape_1", 4), expected);
  }
}

// --- topkids ---------------------------------------------------------------------------------

void WriteTopKidsTree(const std::string& root) {
  WriteText(root + "/kid00.off", Tetrahedron(2));  // 6 vertices
  WriteText(root + "/kid01.off", Tetrahedron());
  WriteText(root + "/kid01_ref.txt", "1 6\n2 1\n4 3\n");
  WriteText(root + "/kid02.off", Tetrahedron(1));
  WriteText(root + "/kid02_ref.txt", "5 2\n");
}

TEST(TopKids, EachKidOntoTheNullShapeWithItsReferenceRows) {
  TempDir dir;
  WriteTopKidsTree(dir.path());
  auto dataset = Create("{type: topkids, root: " + dir.path() + "}");
  const DatasetIndex index = dataset->Load();
  ASSERT_EQ(index.pairs.size(), 2u);
  EXPECT_EQ(index.pairs[0].source, "kid01");
  EXPECT_EQ(index.pairs[0].target, "kid00");
  EXPECT_EQ(index.pairs[1].source, "kid02");
  EXPECT_EQ(index.shapes.size(), 3u);
  const ShapeGroundTruth kid = dataset->GroundTruth(*index.Find("kid01"), 4);
  const ShapeGroundTruth null_shape = dataset->GroundTruth(*index.Find("kid00"), 6);
  const InputGroundTruth pair = PairGroundTruth(kid, "kid01", null_shape, "kid00");
  EXPECT_EQ(pair.source_ids, (std::vector<int>{0, 1, 3}));
  EXPECT_EQ(pair.target_ids, (std::vector<int>{5, 0, 2}));
  EXPECT_TRUE(pair.target_sym_ids.empty());
}

TEST(TopKids, RejectsMalformedInputNamingFileAndLine) {
  {
    TempDir dir;
    WriteTopKidsTree(dir.path());
    ExpectError<InvalidInputError>(
        [&] { Create("{type: topkids, root: " + dir.path() + ", null_shape: kid09}")->Load(); },
        {"no null shape", "kid09"});
    WriteText(dir.path() + "/kid03.off", Tetrahedron());
    ExpectError<InvalidInputError>(
        [&] { Create("{type: topkids, root: " + dir.path() + "}")->Load(); },
        {"kid03_ref.txt", "missing"});
  }
  const std::vector<std::pair<std::string, std::vector<std::string>>> bad_rows = {
      {"1 6\n2 7\n", {":2:", "vertex of kid00 7 out of range [1, 6]"}},
      {"0 6\n", {":1:", "vertex of kid01 0 out of range [1, 4]"}},
      {"1 6 3\n", {":1:", "3 fields"}},
      {"\n\n", {"no rows"}},
  };
  for (const auto& [text, fragments] : bad_rows) {
    TempDir dir;
    WriteTopKidsTree(dir.path());
    WriteText(dir.path() + "/kid01_ref.txt", text);
    auto d = Create("{type: topkids, root: " + dir.path() + "}");
    const DatasetIndex index = d->Load();
    std::vector<std::string> expected = fragments;
    expected.push_back("kid01_ref.txt");
    ExpectError<InvalidInputError>([&] { d->GroundTruth(*index.Find("kid01"), 4); }, expected);
  }
}

}  // namespace
}  // namespace symembed

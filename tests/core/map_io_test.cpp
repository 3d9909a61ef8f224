#include "core/map_io.h"

#include <gtest/gtest.h>

#include "core/errors.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// The message of the InvalidInputError thrown by ParseMap, or "" when it does not throw.
std::string ParseError(const std::string& text, int base, int length, int targets) {
  try {
    ParseMap(text, base, length, targets, "m.map");
  } catch (const InvalidInputError& e) {
    return e.what();
  }
  return "";
}

TEST(MapIo, ReadsOneAndZeroBasedIdsAndIntegralFloats) {
  EXPECT_EQ(ParseMap("1\n3\n2\n", 1, 3, 3, "m"), (std::vector<int>{0, 2, 1}));
  EXPECT_EQ(ParseMap("0\n2\n1", 0, 3, 3, "m"), (std::vector<int>{0, 2, 1}));
  EXPECT_EQ(ParseMap(" 1.0000000e+00 \r\n3.0\n\n\n", 1, -1, -1, "m"), (std::vector<int>{0, 2}));
}

TEST(MapIo, RejectsMalformedEntriesNamingTheLine) {
  EXPECT_NE(ParseError("1\nNaN\n2\n", 1, 3, 3).find("m.map:2: NaN"), std::string::npos);
  EXPECT_NE(ParseError("1\n\n2\n", 1, 3, 3).find("m.map:2: missing"), std::string::npos);
  EXPECT_NE(ParseError("1\nx\n2\n", 1, 3, 3).find("m.map:2: not a number"), std::string::npos);
  EXPECT_NE(ParseError("1\n2.5\n", 1, 2, 3).find("m.map:2: not an integral"), std::string::npos);
  EXPECT_NE(ParseError("1\n4\n", 1, 2, 3).find("m.map:2: vertex id 4 out of range [1, 3]"),
            std::string::npos);
  EXPECT_NE(ParseError("0\n1\n", 1, 2, 3).find("m.map:1: vertex id 0 out of range"),
            std::string::npos);
  EXPECT_NE(ParseError("1\n2\n", 1, 3, 3).find("2 entries, expected 3"), std::string::npos);
  EXPECT_NE(ParseError("", 1, -1, 3).find("empty map"), std::string::npos);
}

TEST(MapIo, WritesOneBasedAndReadsBack) {
  testing::TempDir dir;
  const std::vector<int> map = {4, 0, 2, 2};
  WriteMapFile(dir.File("a_b.map"), map);
  EXPECT_EQ(testing::ReadText(dir.File("a_b.map")), "5\n1\n3\n3\n");
  EXPECT_EQ(ReadMapFile(dir.File("a_b.map"), 1, 4, 5), map);
  EXPECT_THROW(ReadMapFile(dir.File("missing.map"), 1, 4, 5), IoError);
}

}  // namespace
}  // namespace symembed

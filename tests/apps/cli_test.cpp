// The command line's contract: usage errors exit 2, errors exit 1 with one line on stderr.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <vector>

#include "tests/test_util.h"

namespace symembed {
namespace {

using testing::Symembed;

TEST(Cli, NoArgumentsPrintsUsageAndExits2) {
  std::string out;
  EXPECT_EQ(Symembed("", &out), 2);
  EXPECT_NE(out.find("usage: symembed COMMAND"), std::string::npos) << out;
}

TEST(Cli, UnknownCommandExits2WithUsage) {
  std::string out;
  EXPECT_EQ(Symembed("frobnicate", &out), 2);
  EXPECT_NE(out.find("unknown command 'frobnicate'"), std::string::npos) << out;
  EXPECT_NE(out.find("validate"), std::string::npos) << out;
}

TEST(Cli, UnknownFlagExits2) {
  std::string out;
  EXPECT_EQ(Symembed("stages --bogus", &out), 2);
  EXPECT_NE(out.find("unknown option --bogus"), std::string::npos) << out;
}

TEST(Cli, StagesListsSortedKindNameDescription) {
  std::string out;
  ASSERT_EQ(Symembed("stages", &out), 0) << out;
  std::vector<std::string> lines;
  std::istringstream in(out);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  EXPECT_TRUE(std::is_sorted(lines.begin(), lines.end())) << out;
}

// Every option with its default, read only when given ones included, under the dotted names a
// config uses; and docs/options.md is exactly `stages --markdown`.
TEST(Cli, StagesListOptionsWithDefaultsAndDocsOptionsIsCurrent) {
  std::string out;
  ASSERT_EQ(Symembed("stages --options", &out), 0) << out;
  for (const char* line : {"  relaxation: 1.9\n", "  terms.refined_maps.zoomout.k_start: 20\n",
                           "  cross_class: 0\n", "  glue_bridges: 8\n",
                           "  distance_confidence: 0\n", "  root: (required)\n"}) {
    EXPECT_NE(out.find(line), std::string::npos) << line << out;
  }
  std::string markdown;
  ASSERT_EQ(Symembed("stages --markdown 2>/dev/null", &markdown), 0) << markdown;
  EXPECT_NE(markdown.find("`terms.refined_maps.weight: 1`,"), std::string::npos);
  EXPECT_NE(markdown.find("`candidate_errors`,"), std::string::npos);
  EXPECT_NE(markdown.find("`flipped_pairs.total`,"), std::string::npos);
  // Descriptions are text, not Markdown: "Data/<SET>/Meshes" is not a tag, "*.vts" no emphasis.
  EXPECT_NE(markdown.find("Data/\\<SET\\>/Meshes, Corrs/\\*.pid"), std::string::npos);
  EXPECT_TRUE(markdown == testing::ReadText(testing::SourceDir() + "/docs/options.md"))
      << "docs/options.md is not the output of `symembed stages --markdown`: regenerate it with "
         "build/release/symembed stages --markdown > docs/options.md";
}

}  // namespace
}  // namespace symembed

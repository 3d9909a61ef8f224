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

}  // namespace
}  // namespace symembed

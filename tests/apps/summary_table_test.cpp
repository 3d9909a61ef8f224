// scripts/summary-table: the quickstart's readable summary of comparison.csv.
#include <gtest/gtest.h>

#include <string>

#include "tests/test_util.h"

namespace symembed {
namespace {

std::string Script() { return "python3 " + testing::SourceDir() + "/scripts/summary-table "; }

TEST(SummaryTable, PrintsOneShortRowPerVariantWithThreeSignificantDigits) {
  testing::TempDir dir;
  testing::WriteText(
      dir.File("comparison.csv"),
      "variant,pairs,failed_pairs,mean_direct,median_direct,mean_flip_tolerant,pct_direct_0.05,"
      "pct_direct_0.10,pct_direct_0.25,flipped_left_right,flipped_front_back,flipped_up_down,"
      "time_per_pair_s\n"
      "base,12,0,0.069265856,0.016,0.024183564,83.291246,91.708754,93.783069,0,1,0,0.22078488\n"
      "other,12,2,0.02,0.01,0.02,89.2,99.0,100,0,0,0,0.00805\n");
  std::string out;
  ASSERT_EQ(testing::RunShell(Script() + dir.path(), &out), 0) << out;
  EXPECT_NE(out.find("mean direct"), std::string::npos) << out;
  EXPECT_NE(out.find("base"), std::string::npos) << out;
  EXPECT_NE(out.find("0.0693"), std::string::npos) << out;  // three significant digits
  EXPECT_EQ(out.find("0.069265856"), std::string::npos) << out;
  EXPECT_NE(out.find("83.3 / 91.7 / 93.8"), std::string::npos) << out;
  EXPECT_NE(out.find("0 / 1 / 0"), std::string::npos) << out;
  EXPECT_NE(out.find("0.0200"), std::string::npos) << out;  // trailing zeros kept
  EXPECT_NE(out.find("12 (2 failed)"), std::string::npos) << out;
  EXPECT_EQ(out.find("median"), std::string::npos) << out;  // the short table only
}

TEST(SummaryTable, MissingComparisonIsAnErrorNamingTheFolder) {
  testing::TempDir dir;
  std::string out;
  EXPECT_EQ(testing::RunShell(Script() + dir.path(), &out), 1);
  EXPECT_NE(out.find("no comparison.csv in " + dir.path()), std::string::npos) << out;
}

}  // namespace
}  // namespace symembed

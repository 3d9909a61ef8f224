// scripts/pick-by-flip-score: per pair, the run whose chosen rotation the flip stage scored
// lowest.
#include <gtest/gtest.h>

#include <string>

#include "tests/test_util.h"

namespace symembed {
namespace {

std::string Script() { return "python3 " + testing::SourceDir() + "/scripts/pick-by-flip-score "; }

const char kHeader[] = "source,target,status,mean_direct,chosen,oracle,flip_message\n";

// A pairs.csv row: the flip stage's scores of I, Rx, Ry, Rz and its choice.
std::string Row(const std::string& pair, const std::string& status, double error, int chosen,
                int oracle, const std::string& scores) {
  return pair + "," + status + "," + std::to_string(error) + "," + std::to_string(chosen) + "," +
         std::to_string(oracle) + ",\"extrinsic scores [I, Rx, Ry, Rz]: " + scores +
         "; refined_maps 0.1/0.2\"\n";
}

// Run a is better on pair p (lower error), run b on pair q; the scores of the chosen rotations
// point the same way on p, and on q the lower score is b's although a's own lowest score (of a
// rotation a did not choose) is lower still: the chosen rotation's score decides. Pair r failed
// in b and is left out.
TEST(PickByFlipScore, TakesPerPairTheRunWhoseChosenRotationScoresLowest) {
  testing::TempDir dir;
  testing::WriteText(dir.File("a/pairs.csv"),
                     std::string(kHeader) + Row("p1,p2", "ok", 0.02, 0, 0, "0.1 0.9 0.8 0.7") +
                         Row("q1,q2", "ok", 0.50, 1, 0, "0.05 0.6 0.9 0.9") +
                         Row("r1,r2", "ok", 0.10, 0, 0, "0.2 0.9 0.9 0.9"));
  testing::WriteText(dir.File("b/pairs.csv"),
                     std::string(kHeader) + Row("p1,p2", "ok", 0.30, 2, 0, "0.9 0.9 0.4 0.9") +
                         Row("q1,q2", "ok", 0.04, 0, 0, "0.3 0.9 0.9 0.9") +
                         Row("r1,r2", "failed", 0.0, 0, 0, "0 0 0 0"));
  std::string out;
  ASSERT_EQ(testing::RunShell(Script() + dir.File("a") + " " + dir.File("b"), &out), 0) << out;
  EXPECT_NE(out.find("/a: 2 pairs, mean direct 0.2600, chosen != oracle 1"), std::string::npos)
      << out;
  EXPECT_NE(out.find("/b: 2 pairs, mean direct 0.1700, chosen != oracle 1"), std::string::npos)
      << out;
  EXPECT_NE(out.find("chosen by flip score: 2 pairs, mean direct 0.0300, chosen != oracle 0; "
                     "pairs taken from each run: 1, 1"),
            std::string::npos)
      << out;
  EXPECT_NE(out.find("best run per pair (ground truth): mean direct 0.0300"), std::string::npos)
      << out;
  EXPECT_NE(out.find("left out: 1 pairs"), std::string::npos) << out;
}

TEST(PickByFlipScore, ARunWithoutScoresOrWithoutPairsCsvIsAnError) {
  testing::TempDir dir;
  testing::WriteText(dir.File("a/pairs.csv"),
                     std::string(kHeader) + Row("p1,p2", "ok", 0.02, 0, 0, "0.1 0.9 0.8 0.7"));
  testing::WriteText(dir.File("b/pairs.csv"),
                     std::string(kHeader) + "p1,p2,ok,0.02,0,0,oracle: rotation 0\n");
  std::string out;
  EXPECT_EQ(testing::RunShell(Script() + dir.File("a") + " " + dir.File("b"), &out), 1);
  EXPECT_NE(out.find("has no flip scores"), std::string::npos) << out;
  EXPECT_EQ(testing::RunShell(Script() + dir.File("a") + " " + dir.File("c"), &out), 1);
  EXPECT_NE(out.find("no pairs.csv in " + dir.File("c")), std::string::npos) << out;
  EXPECT_EQ(testing::RunShell(Script() + dir.File("a"), &out), 2);
}

}  // namespace
}  // namespace symembed

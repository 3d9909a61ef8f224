// scripts/flip-rules: other front-back decisions replayed on the measures in flip_message.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "tests/test_util.h"

namespace symembed {
namespace {

std::string Script() { return "python3 " + testing::SourceDir() + "/scripts/flip-rules "; }

const char kHeader[] = "source,target,status,chosen,oracle,candidate_errors,flip_message\n";

// A FAUST anisotropic pair's measures: the long-axis measure favours Rx / Rz, the pairs' lower
// distortions I / Ry (0.062 against 0.211), and the stage chose Ry, the oracle's rotation, because
// the distortions ruled the other pair out ("long axis by distortion").
const char kMeasures[] =
    "refined_maps 0.062159/0.83837/0.765499 0.219193/0.828294/0.560817 "
    "0.0820664/0.753072/0.775741 0.210825/0.854546/0.637655; "
    "long_axis 0.632086 0.485822 0.666398 0.472518";
const char kVote[] = "; front_back_vote -0.119762 -0.0540678 0.119762 0.0540678";

std::string Row(const std::string& marker) {
  return std::string("a,b,ok,2,2,0.40575295 0.58821514 0.081653414 0.57156429,\"") + kMeasures +
         marker + kVote + "\"\n";
}

// The `mismatch` column of the file's line (the second line, after the header: its folder, the
// pairs, the mismatches): how many pairs today's totals choose otherwise than the stage did.
int Mismatches(const std::string& out) {
  std::istringstream in(out.substr(out.find('\n') + 1));
  std::string folder;
  int pairs = -1, mismatch = -1;
  in >> folder >> pairs >> mismatch;
  EXPECT_EQ(pairs, 1) << out;
  return mismatch;
}

TEST(FlipRules, TodaysTotalsRuleOutThePairTheDistortionsRuledOut) {
  testing::TempDir dir;
  testing::WriteText(dir.File("ruled/pairs.csv"), kHeader + Row("; long axis by distortion"));
  testing::WriteText(dir.File("plain/pairs.csv"), kHeader + Row(""));
  std::string ruled, plain;
  ASSERT_EQ(testing::RunShell(Script() + dir.File("ruled/pairs.csv"), &ruled), 0) << ruled;
  ASSERT_EQ(testing::RunShell(Script() + dir.File("plain/pairs.csv"), &plain), 0) << plain;
  // With the marker the replay chooses Ry as the stage did; without it the long-axis measure
  // turns the pair (Rz), which the stage's choice contradicts.
  EXPECT_EQ(Mismatches(ruled), 0) << ruled;
  EXPECT_EQ(Mismatches(plain), 1) << plain;
}

}  // namespace
}  // namespace symembed

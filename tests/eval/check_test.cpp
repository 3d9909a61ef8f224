#include "eval/baseline.h"

#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <vector>

#include "core/errors.h"
#include "eval/report.h"
#include "harness/config.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

VariantSummary BaseSummary() {
  VariantSummary s;
  s.variant = "base";
  s.evaluation_geodesics = "fast_marching";
  s.pairs = 10;
  s.mean_direct = 0.05;
  s.median_direct = 0.04;
  s.mean_flip_tolerant = 0.045;
  s.pct_direct = {40.0, 70.0, 99.0};
  s.pct_flip_tolerant = {45.0, 75.0, 99.5};
  s.auc_direct = 0.7;
  s.flipped_left_right = 1;
  return s;
}

JsonValue Json(const VariantSummary& s) { return SummaryToJson(s); }

// The checked metrics are the summary entries that carry a check, in the summary's order, with
// these directions and default tolerances.
TEST(Check, CheckedMetricsAreTheSummaryEntriesWithACheck) {
  const std::vector<std::tuple<std::string, bool, double>> expected = {
      {"failed_pairs", false, 0.0},          {"mean_direct", false, 0.002},
      {"median_direct", false, 0.002},       {"mean_flip_tolerant", false, 0.002},
      {"pct_direct.0.05", true, 1.0},        {"pct_direct.0.10", true, 1.0},
      {"pct_direct.0.25", true, 1.0},        {"pct_flip_tolerant.0.05", true, 1.0},
      {"pct_flip_tolerant.0.10", true, 1.0}, {"pct_flip_tolerant.0.25", true, 1.0},
      {"auc_direct", true, 0.005},           {"flipped_pairs.left_right", false, 0.0},
      {"flipped_pairs.front_back", false, 0.0}, {"flipped_pairs.up_down", false, 0.0},
      {"flipped_pairs.total", false, 0.0}};
  std::vector<std::tuple<std::string, bool, double>> actual;
  for (const CheckedMetric& m : CheckedMetrics()) {
    actual.emplace_back(m.key, m.higher_is_better, m.tolerance);
  }
  EXPECT_EQ(actual, expected);
  size_t checked = 0;
  for (const SummaryEntry& e : SummaryEntries()) checked += e.check ? 1 : 0;
  EXPECT_EQ(checked, CheckedMetrics().size());
}

TEST(Check, EqualAndBetterPassWorseFails) {
  const VariantSummary base = BaseSummary();
  EXPECT_FALSE(CompareSummaries(Json(base), Json(base)).worse);
  VariantSummary better = base;
  better.mean_direct = 0.03;
  better.pct_direct[0] = 60.0;
  better.flipped_left_right = 0;
  better.time_total_s = 1e6;  // timings are not checked
  EXPECT_FALSE(CompareSummaries(Json(base), Json(better)).worse);

  VariantSummary worse = base;
  worse.mean_direct = 0.06;  // +0.01 > 0.002
  const CheckResult r = CompareSummaries(Json(base), Json(worse));
  EXPECT_TRUE(r.worse);
  EXPECT_NE(FormatCheck(r).find("mean_direct"), std::string::npos);
  EXPECT_NE(FormatCheck(r).find("WORSE"), std::string::npos);
  // A looser tolerance accepts it.
  EXPECT_FALSE(CompareSummaries(Json(base), Json(worse), {{"mean_direct", 0.02}}).worse);

  VariantSummary fewer = base;
  fewer.pct_flip_tolerant[1] = 70.0;  // -5 points > 1
  EXPECT_TRUE(CompareSummaries(Json(base), Json(fewer)).worse);
  EXPECT_FALSE(CompareSummaries(Json(base), Json(fewer), {{"pct_flip_tolerant", 10}}).worse);

  VariantSummary flipped = base;
  flipped.flipped_up_down = 1;
  EXPECT_TRUE(CompareSummaries(Json(base), Json(flipped)).worse);

  VariantSummary other_points = base;
  other_points.points_option = 1024;
  const CheckResult noted = CompareSummaries(Json(base), Json(other_points));
  EXPECT_FALSE(noted.worse);
  ASSERT_EQ(noted.notes.size(), 1u);
  EXPECT_NE(noted.notes[0].find("evaluation_points"), std::string::npos);

  VariantSummary within = base;
  within.mean_direct = 0.0515;  // +0.0015 <= 0.002
  EXPECT_FALSE(CompareSummaries(Json(base), Json(within)).worse);
}

TEST(Check, ToleranceSpecs) {
  const auto t = ParseTolerances({"mean_direct=0.01", "pct_direct.0.05=2", "flipped_pairs=1"});
  EXPECT_EQ(t.at("mean_direct"), 0.01);
  EXPECT_EQ(t.at("pct_direct.0.05"), 2.0);
  EXPECT_THROW(ParseTolerances({"nonsense=1"}), ConfigError);
  EXPECT_THROW(ParseTolerances({"mean_direct"}), ConfigError);
  EXPECT_THROW(ParseTolerances({"mean_direct=-1"}), ConfigError);
}

TEST(Check, CommandExitCodesAndUpdate) {
  testing::TempDir dir;
  const std::string baseline = dir.File("baseline.json");
  const std::string same = dir.File("same.json"), worse = dir.File("worse.json");
  WriteSummaryJson(baseline, BaseSummary());
  WriteSummaryJson(same, BaseSummary());
  VariantSummary w = BaseSummary();
  w.median_direct = 0.08;
  WriteSummaryJson(worse, w);
  const std::string bin = SYMEMBED_BINARY;
  std::string out;
  EXPECT_EQ(testing::RunShell(bin + " check " + same + " --baseline " + baseline, &out), 0) << out;
  EXPECT_NE(out.find("check: OK"), std::string::npos) << out;
  EXPECT_EQ(testing::RunShell(bin + " check " + worse + " --baseline " + baseline, &out), 1)
      << out;
  EXPECT_NE(out.find("median_direct"), std::string::npos) << out;
  EXPECT_NE(out.find("0.04 -> 0.08"), std::string::npos) << out;
  EXPECT_EQ(testing::RunShell(bin + " check " + worse + " --baseline " + baseline +
                                  " --tolerance median_direct=0.1,mean_direct=0.1",
                              &out),
            0)
      << out;
  EXPECT_EQ(testing::RunShell(bin + " check " + worse + " --baseline " + baseline +
                                  " --tolerance bogus=1",
                              &out),
            2)
      << out;
  // --update rewrites the baseline; afterwards the same summary passes.
  EXPECT_EQ(testing::RunShell(bin + " check " + worse + " --baseline " + baseline + " --update",
                              &out),
            0)
      << out;
  EXPECT_EQ(testing::ReadText(baseline), testing::ReadText(worse));
  EXPECT_EQ(testing::RunShell(bin + " check " + worse + " --baseline " + baseline, &out), 0)
      << out;
}

// Input check cannot trust gets exit code 3, never the 1 of a regression.
// A baseline that checks nothing would pass every summary: one without metrics, a metric group
// that is not an object, a key given twice, a number out of range are malformed (exit 3).
TEST(Check, BaselinesWithoutMetricsOrWithMalformedGroupsExit3) {
  testing::TempDir dir;
  const std::string summary = dir.File("summary.json");
  WriteSummaryJson(summary, BaseSummary());
  const std::string good = testing::ReadText(summary);
  const std::string bin = SYMEMBED_BINARY;
  auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"{}", "no metric of a summary.json"},
      {"{\"source\": \"a\", \"target\": \"b\", \"status\": \"ok\"}", "no metric"},
      {replaced("\"pct_direct\": {", "\"pct_direct\": \"x\", \"unused\": {"),
       "pct_direct: expected an object of metrics, got \"x\""},
      {replaced("\"flipped_pairs\": {", "\"flipped_pairs\": [1], \"unused\": {"),
       "flipped_pairs: expected an object of metrics, got [1]"},
      {replaced("\"pairs\": 10,", "\"pairs\": 10, \"mean_direct\": 0.01,"),
       "duplicate key \"mean_direct\""},
      {replaced("\"auc_direct\": 0.7", "\"auc_direct\": 1e400"), "out of range"},
  };
  for (const auto& [text, message] : cases) {
    testing::WriteText(dir.File("baseline.json"), text);
    std::string out;
    EXPECT_EQ(testing::RunShell(bin + " check " + summary + " --baseline " +
                                    dir.File("baseline.json"),
                                &out),
              3)
        << text << "\n" << out;
    EXPECT_NE(out.find(message), std::string::npos) << text << "\n" << out;
  }
}

TEST(Check, MalformedOrUnfinishedInputExits3) {
  testing::TempDir dir;
  const std::string baseline = dir.File("baseline.json");
  WriteSummaryJson(baseline, BaseSummary());
  const std::string bin = SYMEMBED_BINARY;
  std::string text = testing::ReadText(baseline);
  const size_t at = text.find("\"mean_direct\": ") + 15;
  text.replace(at, text.find(',', at) - at, "\"abc\"");
  testing::WriteText(dir.File("abc.json"), text);
  std::string out;
  EXPECT_EQ(testing::RunShell(bin + " check " + dir.File("abc.json") + " --baseline " + baseline,
                              &out),
            3)
      << out;
  EXPECT_NE(out.find(dir.File("abc.json") + ": mean_direct: expected a number or null, got \"abc\""),
            std::string::npos)
      << out;
  EXPECT_EQ(testing::RunShell(bin + " check " + baseline + " --baseline " + dir.File("abc.json"),
                              &out),
            3)
      << out;
  EXPECT_EQ(testing::RunShell(bin + " check " + dir.File("missing.json") + " --baseline " +
                                  baseline,
                              &out),
            3)
      << out;
  testing::WriteText(dir.File("run/base/summary.json"), testing::ReadText(baseline));
  testing::WriteText(dir.File("run/base/IN_PROGRESS"), "symembed run\n");
  EXPECT_EQ(testing::RunShell(bin + " check " + dir.File("run/base/summary.json") + " --baseline " +
                                  baseline,
                              &out),
            3)
      << out;
  EXPECT_NE(out.find(dir.File("run/base") + ": the folder is incomplete"), std::string::npos)
      << out;
}

}  // namespace
}  // namespace symembed

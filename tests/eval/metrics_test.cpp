#include "eval/metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <utility>

#include "eval/json.h"
#include "eval/report.h"
#include "harness/config.h"
#include "harness/run_outputs.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// Sums of a few doubles: exact up to a few ulps.
constexpr double kTol = 1e-12;

PairEvaluation MakePair(const std::string& s, const std::string& t, std::vector<double> direct,
                        std::vector<double> sym = {}) {
  PairEvaluation p;
  p.source = s;
  p.target = t;
  p.ok = true;
  p.errors_direct = std::move(direct);
  p.errors_sym = std::move(sym);
  ComputePairStatistics(p);
  p.flip = ClassifyFlip(-1, -1, p.has_sym, p.mean_direct, p.mean_sym);
  return p;
}

TEST(Metrics, BasicStatistics) {
  EXPECT_NEAR(Mean({0.1, 0.2, 0.6}), 0.3, kTol);
  EXPECT_DOUBLE_EQ(Median({0.3, 0.1, 0.2}), 0.2);
  EXPECT_DOUBLE_EQ(Median({0.4, 0.1, 0.2, 0.3}), 0.25);
  EXPECT_DOUBLE_EQ(PercentAtMost({0.0, 0.05, 0.06, 0.3}, 0.05), 50.0);
  EXPECT_TRUE(std::isnan(Mean({})));
}

TEST(Metrics, CurveAndArea) {
  const auto t = CurveThresholds(0.25, 0.0025);
  ASSERT_EQ(t.size(), 101u);
  EXPECT_DOUBLE_EQ(t.front(), 0.0);
  EXPECT_DOUBLE_EQ(t.back(), 0.25);
  // Perfect map: every threshold covers every point, area 1.
  const auto perfect = CumulativeCurve({0.0, 0.0, 0.0}, t);
  EXPECT_DOUBLE_EQ(perfect.front(), 1.0);
  EXPECT_NEAR(CurveArea(t, perfect), 1.0, kTol);
  // Errors 0 and 1 (beyond the range): curve is 0.5 everywhere, area 0.5.
  const auto half = CumulativeCurve({0.0, 1.0}, t);
  EXPECT_DOUBLE_EQ(half[50], 0.5);
  EXPECT_NEAR(CurveArea(t, half), 0.5, kTol);
  // Hand-computed on a coarse curve: thresholds {0, 0.1, 0.2}, errors {0.05, 0.15}.
  const std::vector<double> coarse = {0.0, 0.1, 0.2};
  const auto c = CumulativeCurve({0.05, 0.15}, coarse);
  EXPECT_EQ(c, (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_NEAR(CurveArea(coarse, c), (0.025 + 0.075) / 0.2, kTol);
}

TEST(Metrics, FlipClassFromCandidates) {
  // Candidates: 0 = I, 1 = Rx, 2 = Ry, 3 = Rz; canonical y = up-down, z = front-back.
  EXPECT_EQ(ClassifyFlip(1, 0, false, 0, 0), FlipClass::kUpDown);     // Rx negates y and z
  EXPECT_EQ(ClassifyFlip(0, 2, false, 0, 0), FlipClass::kFrontBack);  // Ry negates x and z
  EXPECT_EQ(ClassifyFlip(3, 0, false, 0, 0), FlipClass::kUpDown);     // Rz negates x and y
  EXPECT_EQ(ClassifyFlip(1, 3, false, 0, 0), FlipClass::kFrontBack);  // Rx Rz^T = Ry
  // Same candidate or unknown: decided by the symmetric ground truth.
  EXPECT_EQ(ClassifyFlip(2, 2, true, 0.3, 0.1), FlipClass::kLeftRight);
  EXPECT_EQ(ClassifyFlip(-1, 2, true, 0.1, 0.3), FlipClass::kNone);
  EXPECT_EQ(ClassifyFlip(-1, -1, false, 0.3, 0.0), FlipClass::kNone);
}

TEST(Metrics, RefineSideComparesTheNearerGroundTruthBeforeAndAfter) {
  PairEvaluation p;
  p.has_sym = true;
  p.mean_direct = 0.05;
  p.mean_sym = 0.4;
  EXPECT_EQ(p.RefineSide(), "");  // not refined
  p.refined = true;
  p.initial_mean_direct = 0.1;
  p.initial_mean_sym = 0.3;
  EXPECT_EQ(p.RefineSide(), "kept");
  p.initial_mean_direct = 0.5;
  p.initial_mean_sym = 0.12;
  EXPECT_EQ(p.RefineSide(), "to_direct");
  std::swap(p.mean_direct, p.mean_sym);
  EXPECT_EQ(p.RefineSide(), "kept");
  p.initial_mean_direct = 0.1;
  p.initial_mean_sym = 0.3;
  EXPECT_EQ(p.RefineSide(), "to_symmetric");
  p.has_sym = false;
  EXPECT_EQ(p.RefineSide(), "");
}

TEST(Metrics, SummaryPoolsAllPointsAndIgnoresOrder) {
  EvaluationOptions options;
  std::vector<PairEvaluation> pairs = {
      MakePair("b", "c", {0.2}, {0.0}),         // left-right flipped
      MakePair("a", "b", {0.0, 0.1}, {0.3, 0.3}),
  };
  PairEvaluation failed;
  failed.source = "a";
  failed.target = "c";
  failed.message = "bad map";
  failed.stage_seconds["evaluation"] = 2.0;
  pairs.push_back(failed);
  const VariantSummary s = Summarize("base", pairs, options, VariantTimings{});
  EXPECT_EQ(s.pairs, 3);
  EXPECT_EQ(s.failed_pairs, 1);
  EXPECT_EQ(s.total_points, 3);
  EXPECT_NEAR(s.mean_direct, 0.1, kTol);                   // (0 + 0.1 + 0.2) / 3
  EXPECT_NEAR(s.mean_flip_tolerant, (0.0 + 0.1 + 0.0) / 3, kTol);
  EXPECT_NEAR(s.mean_of_pair_means_direct, (0.05 + 0.2) / 2, kTol);
  EXPECT_NEAR(s.pct_direct[1], 200.0 / 3, kTol);           // 0 and 0.1 are <= 0.10
  EXPECT_EQ(s.flipped_left_right, 1);
  EXPECT_EQ(s.FlippedTotal(), 1);
  EXPECT_NEAR(s.time_per_pair_s, 2.0 / 3, kTol);
  std::reverse(pairs.begin(), pairs.end());
  const VariantSummary r = Summarize("base", pairs, options, VariantTimings{});
  EXPECT_EQ(WriteJson(SummaryToJson(r)), WriteJson(SummaryToJson(s)));
  EXPECT_EQ(CurveCsv(r), CurveCsv(s));
  EXPECT_EQ(PairsCsv(pairs), PairsCsv({pairs.rbegin(), pairs.rend()}));
}

TEST(Metrics, SummaryJsonRoundTrip) {
  EvaluationOptions options;
  options.points = 64;
  VariantTimings timings;
  timings.total_seconds = 12.5;
  timings.peak_rss_mb = 321.25;
  timings.shape_stage_seconds["a"] = {{"embedding", 1.0}, {"geodesics", 0.5}};
  const VariantSummary s =
      Summarize("v1", {MakePair("a", "b", {0.01, 0.2, 1.0 / 3}, {0.1, 0.1, 0.1})}, options,
                timings);
  testing::TempDir dir;
  WriteSummaryJson(dir.File("summary.json"), s);
  const VariantSummary r = ReadSummaryJson(dir.File("summary.json"));
  // Written back, the round-tripped summary gives the same text (every number exact).
  EXPECT_EQ(WriteJson(SummaryToJson(r)), WriteJson(SummaryToJson(s)));
  EXPECT_EQ(r.points_option, 64);
  EXPECT_EQ(r.mean_direct, s.mean_direct);
  EXPECT_EQ(r.time_per_shape_s, 1.5);
  // The keys scripts rely on.
  const JsonValue j = ParseJson(testing::ReadText(dir.File("summary.json")));
  for (const char* key :
       {"pairs", "failed_pairs", "mean_direct", "median_direct", "mean_flip_tolerant",
        "pct_direct", "pct_flip_tolerant", "auc_direct", "flipped_pairs", "time_total_s",
        "time_per_shape_s", "time_per_pair_s", "peak_rss_mb", "evaluation_geodesics"}) {
    EXPECT_TRUE(j.Has(key)) << key;
  }
  EXPECT_TRUE(j.Get("pct_direct").Get("0.10").IsNumber());
  EXPECT_EQ(j.Get("flipped_pairs").Get("total").AsNumber(), 1.0);  // sym mean 0.1 < 0.18
}

TEST(Metrics, PairRecordRoundTripIsExact) {
  PairEvaluation p = MakePair("cat0", "cat,1 \"x\"", {0.1 + 0.2, 1.0 / 3, 1e-300, 0.0},
                              {2.0 / 3, 0.5, 1e300, 7.0});
  p.chosen = 2;
  p.oracle = 0;
  p.flip = FlipClass::kFrontBack;
  p.stage_seconds = {{"evaluation", 0.123456789}, {"flip", 1.0 / 7}};
  p.stage_messages = {{"flip", "extrinsic scores [I, Rx, Ry, Rz]: 1 2 \"3\" 4"},
                      {"refine", "zoomout k 20..120\nline two"}};
  p.candidate_errors = {0.1, 0.7, 0.3, 1.0 / 3};
  const PairEvaluation r = ParsePairRecord(SerializePairRecord(p));
  EXPECT_EQ(SerializePairRecord(r), SerializePairRecord(p));
  EXPECT_EQ(r.errors_direct, p.errors_direct);
  EXPECT_EQ(r.errors_sym, p.errors_sym);
  EXPECT_EQ(r.stage_seconds, p.stage_seconds);
  EXPECT_EQ(r.stage_messages, p.stage_messages);
  EXPECT_EQ(r.candidate_errors, p.candidate_errors);
  EXPECT_EQ(r.mean_direct, p.mean_direct);
  EXPECT_EQ(r.flip, FlipClass::kFrontBack);
  EXPECT_EQ(r.target, p.target);
  EXPECT_EQ(SerializePairRecord(p).find('\n'), std::string::npos);

  PairEvaluation failed;
  failed.source = "a";
  failed.target = "b";
  failed.message = "map.map:3: NaN entry";
  const PairEvaluation rf = ParsePairRecord(SerializePairRecord(failed));
  EXPECT_FALSE(rf.ok);
  EXPECT_EQ(rf.message, failed.message);
  // Records written before stage messages and candidate errors existed still parse.
  EXPECT_TRUE(rf.stage_messages.empty());
  EXPECT_TRUE(rf.candidate_errors.empty());
}

// A run's record carries the pair's inputs as its first member, without spaces, the other
// members following as WriteJson writes them (the form --resume reads); they read back equal,
// and a record without them has none.
TEST(Metrics, PairRecordCarriesItsInputsFirst) {
  PairEvaluation p = MakePair("cat0", "cat1", {0.25, 0.5}, {});
  const std::string without = SerializePairRecord(p);
  EXPECT_FALSE(ParsePairRecord(without).inputs);
  p.inputs = PairInputs{0x1, 0xfedcba9876543210ULL, 0x0123456789abcdefULL};
  const std::string with = SerializePairRecord(p);
  EXPECT_EQ(with,
            "{\"inputs\":{\"source\":\"0000000000000001\",\"target\":\"fedcba9876543210\","
            "\"pair\":\"0123456789abcdef\"}," +
                without.substr(1));
  const PairEvaluation r = ParsePairRecord(with);
  ASSERT_TRUE(r.inputs);
  EXPECT_EQ(*r.inputs, *p.inputs);
  EXPECT_EQ(SerializePairRecord(r), with);
  // Anywhere in the object and with spaces it is the same member; any other form fails.
  EXPECT_EQ(
      ParsePairRecord("{\"source\": \"a\", \"target\": \"b\", \"ok\": false, \"message\": \"\", "
                      "\"chosen\": -1, \"oracle\": -1, \"stage_seconds\": {}, \"inputs\": "
                      "{\"pair\": \"0000000000000003\", \"source\": \"0000000000000001\", "
                      "\"target\": \"0000000000000002\"}}")
          .inputs,
      (PairInputs{1, 2, 3}));
  for (const char* bad : {"[]", "{}", "{\"source\":\"1\",\"target\":\"2\",\"pair\":\"3\"}",
                          "{\"source\":\"000000000000000G\",\"target\":\"0000000000000002\","
                          "\"pair\":\"0000000000000003\"}",
                          "{\"source\":\"000000000000000A\",\"target\":\"0000000000000002\","
                          "\"pair\":\"0000000000000003\"}"}) {
    EXPECT_THROW(ParsePairRecord("{\"inputs\":" + std::string(bad) + "," + without.substr(1), "r"),
                 InvalidInputError)
        << bad;
  }
}

TEST(Report, ComparisonAndCurvePlots) {
  EvaluationOptions options;
  testing::TempDir dir;
  std::vector<VariantSummary> variants;
  for (const char* name : {"base", "worse"}) {
    const double e = std::string(name) == "base" ? 0.02 : 0.1;
    std::vector<PairEvaluation> pairs = {MakePair("a", "b", {e, 2 * e, 0.3 * e})};
    variants.push_back(Summarize(name, pairs, options, VariantTimings{}));
    WriteVariantOutputs(dir.File(name), variants.back(), pairs, VariantTimings{});
  }
  std::string warning;
  const bool plotted = WriteComparison(dir.path(), variants, &warning);
  const std::string csv = testing::ReadText(dir.File("comparison.csv"));
  EXPECT_EQ(csv.substr(0, csv.find(',')), "variant");
  EXPECT_NE(csv.find("\nworse,1,0,"), std::string::npos) << csv;
  if (testing::RunShell("/usr/bin/python3 -c 'import matplotlib'") != 0) {
    EXPECT_FALSE(plotted);
    GTEST_SKIP() << "no matplotlib for /usr/bin/python3: " << warning;
  }
  EXPECT_TRUE(plotted) << warning;
  EXPECT_FALSE(testing::ReadText(dir.File("curves.png")).empty());
  EXPECT_NE(testing::ReadText(dir.File("curves.svg")).find("<svg"), std::string::npos);
}

// The column tables: every pairs.csv row has the header's fields, a failed pair too, and the
// report reads each column as the table says; every summary entry is written and read back,
// and a summary without a required entry fails naming it.
TEST(Report, ColumnTablesCoverEveryRowAndEntry) {
  PairEvaluation failed;
  failed.source = "a";
  failed.target = "c,\"d\"";
  failed.message = "bad map";
  const std::string csv = PairsCsv({MakePair("a", "b", {0.1, 0.2}, {0.3, 0.0}), failed});
  const auto rows = ParseCsv(csv, "pairs.csv");
  ASSERT_EQ(rows.size(), 3u);
  ASSERT_EQ(rows[0].size(), PairsCsvColumns().size());
  for (size_t c = 0; c < rows[0].size(); ++c) EXPECT_EQ(rows[0][c], PairsCsvColumns()[c].name);
  for (const auto& row : rows) EXPECT_EQ(row.size(), rows[0].size());
  EXPECT_EQ(rows[2][1], "c,\"d\"");
  EXPECT_EQ(rows[2][2], "failed");

  EvaluationOptions options;
  const VariantSummary s =
      Summarize("v", {MakePair("a", "b", {0.01, 0.2}, {0.1, 0.1})}, options, VariantTimings{});
  const JsonValue j = SummaryToJson(s);
  const auto comparison = ParseCsv(ComparisonCsv({s}), "comparison.csv");
  ASSERT_EQ(comparison.size(), 2u);
  EXPECT_EQ(comparison[0].size(), comparison[1].size());
  for (const auto& e : SummaryEntries()) {
    const size_t dot = e.key.find('.');
    const std::string group = dot == std::string::npos ? "" : e.key.substr(0, dot);
    const std::string key = dot == std::string::npos ? e.key : e.key.substr(dot + 1);
    const JsonValue& holder = group.empty() ? j : j.Get(group);
    if (e.key != "shapes_lost_area") {
      EXPECT_TRUE(holder.Has(key)) << e.key;
    }
    EXPECT_EQ(e.read == SummaryEntry::Read::kWritten, !e.from_json) << e.key;
    EXPECT_EQ(e.csv_column.empty(), !e.csv_cell) << e.key;
    if (e.read != SummaryEntry::Read::kRequired) continue;
    // The summary without this entry.
    JsonValue without = JsonValue::Object();
    for (const auto& [name, value] : j.members()) {
      if (name == group) {
        JsonValue members = JsonValue::Object();
        for (const auto& [k, v] : value.members()) {
          if (k != key) members.Set(k, v);
        }
        without.Set(name, members);
      } else if (name != e.key) {
        without.Set(name, value);
      }
    }
    try {
      SummaryFromJson(without, "summary.json");
      ADD_FAILURE() << "no error without " << e.key;
    } catch (const InvalidInputError& error) {
      EXPECT_NE(std::string(error.what()).find(key), std::string::npos) << error.what();
    }
  }
}

TEST(Json, ParseErrorsNameLineAndColumn) {
  try {
    ParseJson("{\n  \"a\": [1, 2,,]\n}", "s.json");
    FAIL() << "expected InvalidInputError";
  } catch (const InvalidInputError& e) {
    EXPECT_NE(std::string(e.what()).find("s.json:2:"), std::string::npos) << e.what();
  }
  EXPECT_THROW(ParseJson("{\"a\": 1} x"), InvalidInputError);
  EXPECT_EQ(ParseJson("\"\\u00e9\\n\"").AsString(), "\xc3\xa9\n");
  EXPECT_TRUE(std::isnan(ParseJson("null").NumberOr(std::nan(""))));
}

// The doubles of the number tests: bit patterns of every exponent, decimal fractions, and the
// extremes (subnormals, the largest, signed zeros).
std::vector<double> TestDoubles() {
  std::vector<double> values = {
      0.0,   -0.0, 5e-324, 2.2250738585072014e-308, 1.7976931348623157e308, 0.1, 0.3, 1.0 / 3.0,
      100.0, 1e21, 1e-5,   123456789012345678.0};
  std::mt19937_64 rng(5);
  for (int i = 0; i < 20000; ++i) {
    const uint64_t bits = rng();
    double x = 0.0;
    std::memcpy(&x, &bits, sizeof x);
    if (std::isfinite(x)) values.push_back(x);
    values.push_back(static_cast<double>(static_cast<int64_t>(bits % 2000001) - 1000000) / 1e4);
  }
  return values;
}

TEST(Json, NumbersAreTheShortestOf15To17DigitsThatReadBack) {
  for (const double x : TestDoubles()) {
    char expected[40];
    for (const int precision : {15, 16, 17}) {
      std::snprintf(expected, sizeof expected, "%.*g", precision, x);
      if (std::strtod(expected, nullptr) == x) break;
    }
    ASSERT_EQ(FormatExactDouble(x), expected);
  }
}

TEST(Json, NumbersReadBackAsStrtodReadsThem) {
  for (const double x : TestDoubles()) {
    const std::string text = FormatExactDouble(x);
    const double back = ParseJson(text).AsNumber();
    ASSERT_EQ(std::memcmp(&back, &x, sizeof x), 0) << text;
  }
  for (const char* text : {"1.5e+3", "-0.25E-2", "-0", "1e-400", "2.5e-320"}) {
    const double x = ParseJson(text).AsNumber();
    const double expected = std::strtod(text, nullptr);
    EXPECT_EQ(std::memcmp(&x, &expected, sizeof x), 0) << text;
  }
  for (const char* bad : {"-", "1e", "1.2.3", "1e400", "-1e999", "1+2", "--1"}) {
    EXPECT_THROW(ParseJson(bad), InvalidInputError) << bad;
  }
}

}  // namespace
}  // namespace symembed

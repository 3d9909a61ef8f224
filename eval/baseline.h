// Accuracy regression check: compares a summary.json with a committed baseline summary.
//
// Each checked metric has a direction and an absolute tolerance; it is WORSE when it moved in
// the bad direction by more than the tolerance (or became NaN / disappeared). Timings are not
// checked (they depend on the machine).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "eval/json.h"

namespace symembed {

struct CheckedMetric {
  std::string key;          // flattened: "mean_direct", "pct_direct.0.05", "flipped_pairs.total"
  bool higher_is_better = false;
  double tolerance = 0.0;   // default absolute tolerance
};

// The checked metrics with their default tolerances: the entries of the summary's table that
// carry a check (eval/report.h SummaryEntries), in the summary's order:
//   failed_pairs 0; mean_direct, median_direct, mean_flip_tolerant 0.002 (of sqrt(area));
//   pct_direct.*, pct_flip_tolerant.* 1.0 (percentage points); auc_direct 0.005;
//   flipped_pairs.{left_right, front_back, up_down, total} 0 (pairs).
const std::vector<CheckedMetric>& CheckedMetrics();

// Parses "KEY=VALUE" overrides. KEY is a checked key or a group prefix ("pct_direct" sets all
// of pct_direct.*); VALUE >= 0. Throws ConfigError listing the known keys.
std::map<std::string, double> ParseTolerances(const std::vector<std::string>& specs);

struct MetricComparison {
  std::string key;
  double baseline = 0.0, current = 0.0, tolerance = 0.0;
  bool higher_is_better = false;
  bool in_baseline = true, in_current = true;
  bool worse = false;
};

struct CheckResult {
  std::vector<MetricComparison> metrics;
  bool worse = false;               // any metric worse
  std::vector<std::string> notes;   // evaluation settings that differ (not failures)
};

// Checks that `summary` is a JSON object whose checked metrics, where present, are numbers or
// null (NaN). Throws InvalidInputError naming `where` and the key otherwise.
void ValidateSummary(const JsonValue& summary, const std::string& where);

// Compares two parsed summaries; tolerances override the defaults (keys as ParseTolerances).
CheckResult CompareSummaries(const JsonValue& baseline, const JsonValue& current,
                             const std::map<std::string, double>& tolerances = {});

// One line per metric: "key  old -> new  (tolerance t)  OK|WORSE|NEW", the notes, then a
// verdict line.
std::string FormatCheck(const CheckResult& result);

}  // namespace symembed

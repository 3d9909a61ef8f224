#include "eval/baseline.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "core/errors.h"
#include "eval/report.h"

namespace symembed {

const std::vector<CheckedMetric>& CheckedMetrics() {
  static const std::vector<CheckedMetric> metrics = [] {
    std::vector<CheckedMetric> m;
    for (const SummaryEntry& e : SummaryEntries()) {
      if (e.check) m.push_back({e.key, e.check->higher_is_better, e.check->tolerance});
    }
    return m;
  }();
  return metrics;
}

namespace {

std::string KnownKeys() {
  std::string out;
  for (const auto& m : CheckedMetrics()) out += (out.empty() ? "" : ", ") + m.key;
  return out;
}

bool InGroup(const std::string& key, const std::string& prefix) {
  return key == prefix || (key.size() > prefix.size() && key.compare(0, prefix.size(), prefix) == 0 &&
                           key[prefix.size()] == '.');
}

// The value of a flattened key ("group.sub": only the first dot separates, "0.05" has its own).
// A metric of a summary ("mean_direct", or "pct_direct.0.05" in the group "pct_direct"), or
// nullptr when absent. Throws InvalidInputError naming `where` when the metric's group is there
// but is not an object (it would hide its metrics as absent).
const JsonValue* Lookup(const JsonValue& summary, const std::string& key,
                        const std::string& where) {
  if (summary.Has(key)) return &summary.Get(key);
  const size_t dot = key.find('.');
  if (dot == std::string::npos) return nullptr;
  const std::string name = key.substr(0, dot);
  if (!summary.Has(name)) return nullptr;
  const JsonValue& group = summary.Get(name);
  if (!group.IsObject()) {
    throw InvalidInputError(where + ": " + name + ": expected an object of metrics, got " +
                            WriteJson(group, 0));
  }
  const std::string sub = key.substr(dot + 1);
  return group.Has(sub) ? &group.Get(sub) : nullptr;
}

std::string Format(double x) {
  if (std::isnan(x)) return "nan";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

}  // namespace

std::map<std::string, double> ParseTolerances(const std::vector<std::string>& specs) {
  std::map<std::string, double> tolerances;
  for (const auto& spec : specs) {
    const size_t eq = spec.find('=');
    if (eq == std::string::npos) {
      throw ConfigError("tolerance '" + spec + "' must be KEY=VALUE; keys: " + KnownKeys());
    }
    const std::string key = spec.substr(0, eq), value_text = spec.substr(eq + 1);
    char* end = nullptr;
    const double value = std::strtod(value_text.c_str(), &end);
    if (value_text.empty() || *end != '\0' || !(value >= 0) || !std::isfinite(value)) {
      throw ConfigError("tolerance '" + spec + "': VALUE must be a number >= 0");
    }
    bool known = false;
    for (const auto& m : CheckedMetrics()) known = known || InGroup(m.key, key);
    if (!known) {
      throw ConfigError("tolerance '" + spec + "': unknown key '" + key + "'; keys: " +
                        KnownKeys() + " (or a group: pct_direct, pct_flip_tolerant, " +
                        "flipped_pairs)");
    }
    tolerances[key] = value;
  }
  return tolerances;
}

void ValidateSummary(const JsonValue& summary, const std::string& where) {
  if (!summary.IsObject()) throw InvalidInputError(where + ": expected a JSON object");
  int numbers = 0;
  for (const auto& metric : CheckedMetrics()) {
    const JsonValue* value = Lookup(summary, metric.key, where);
    if (value && !value->IsNumber() && !value->IsNull()) {
      throw InvalidInputError(where + ": " + metric.key + ": expected a number or null, got " +
                              WriteJson(*value, 0));
    }
    if (value && value->IsNumber()) ++numbers;
  }
  if (numbers == 0) {
    throw InvalidInputError(where + ": no metric of a summary.json (" + KnownKeys() +
                            "): not a summary");
  }
}

CheckResult CompareSummaries(const JsonValue& baseline, const JsonValue& current,
                             const std::map<std::string, double>& tolerances) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CheckResult result;
  for (const auto& metric : CheckedMetrics()) {
    MetricComparison c;
    c.key = metric.key;
    c.higher_is_better = metric.higher_is_better;
    c.tolerance = metric.tolerance;
    // A group override applies first, an exact key override wins.
    for (const auto& [key, value] : tolerances) {
      if (key != metric.key && InGroup(metric.key, key)) c.tolerance = value;
    }
    if (auto it = tolerances.find(metric.key); it != tolerances.end()) c.tolerance = it->second;
    const JsonValue* old_value = Lookup(baseline, metric.key, "baseline");
    const JsonValue* new_value = Lookup(current, metric.key, "summary");
    c.in_baseline = old_value != nullptr;
    c.in_current = new_value != nullptr;
    c.baseline = old_value ? old_value->NumberOr(nan) : nan;
    c.current = new_value ? new_value->NumberOr(nan) : nan;
    if (!c.in_baseline || std::isnan(c.baseline)) {
      c.worse = false;  // nothing to compare with
    } else if (!c.in_current || std::isnan(c.current)) {
      c.worse = true;
    } else {
      const double change = c.higher_is_better ? c.baseline - c.current : c.current - c.baseline;
      c.worse = change > c.tolerance;
    }
    result.worse = result.worse || c.worse;
    result.metrics.push_back(c);
  }
  // Numbers measured differently are not comparable; say so without failing.
  for (const char* key : {"evaluation_geodesics", "evaluation_points", "max_error", "step"}) {
    const std::string old_text = WriteJson(baseline.Get(key), 0);
    const std::string new_text = WriteJson(current.Get(key), 0);
    if (baseline.Has(key) && current.Has(key) && old_text != new_text) {
      result.notes.push_back(std::string("note: ") + key + " differs: " + old_text + " -> " +
                             new_text);
    }
  }
  return result;
}

std::string FormatCheck(const CheckResult& result) {
  size_t width = 0;
  for (const auto& c : result.metrics) width = std::max(width, c.key.size());
  std::ostringstream out;
  for (const auto& c : result.metrics) {
    out << c.key << std::string(width + 2 - c.key.size(), ' ');
    out << (c.in_baseline ? Format(c.baseline) : "-") << " -> "
        << (c.in_current ? Format(c.current) : "missing");
    out << "  (tolerance " << Format(c.tolerance) << ", "
        << (c.higher_is_better ? "higher" : "lower") << " is better)  ";
    if (!c.in_baseline || std::isnan(c.baseline)) {
      out << "NEW";
    } else {
      out << (c.worse ? "WORSE" : "OK");
    }
    out << "\n";
  }
  for (const auto& note : result.notes) out << note << "\n";
  out << (result.worse ? "check: WORSE than the baseline\n" : "check: OK\n");
  return out.str();
}

}  // namespace symembed

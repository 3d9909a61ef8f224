// symembed check SUMMARY --baseline FILE [--tolerance KEY=VALUE ...] [--update]
#include <filesystem>
#include <iostream>
#include <sstream>

#include "apps/args.h"
#include "apps/commands.h"
#include "core/errors.h"
#include "core/files.h"
#include "eval/baseline.h"
#include "eval/json.h"
#include "eval/report.h"
#include "harness/run_outputs.h"

namespace symembed {

namespace {

constexpr int kMalformedInput = 3;  // exit code: a file check could not read or trust

std::string ToleranceHelp() {
  std::ostringstream out;
  out << "absolute tolerance of a metric, KEY=VALUE; repeatable and comma-separated lists "
         "allowed; KEY may be a group (pct_direct, pct_flip_tolerant, flipped_pairs). "
         "Defaults:";
  for (const auto& m : CheckedMetrics()) {
    out << "\n        " << m.key << "=" << m.tolerance << " ("
        << (m.higher_is_better ? "higher" : "lower") << " is better)";
  }
  return out.str();
}

// --tolerance may repeat; ArgParser keeps one value per option, so collect them here.
std::vector<std::string> TakeTolerances(Args& args) {
  std::vector<std::string> specs;
  Args rest;
  for (size_t i = 0; i < args.size(); ++i) {
    std::string value;
    if (args[i] == "--tolerance") {
      if (i + 1 >= args.size()) throw UsageError{"option --tolerance needs a value"};
      value = args[++i];
    } else if (args[i].rfind("--tolerance=", 0) == 0) {
      value = args[i].substr(12);
    } else {
      rest.push_back(args[i]);
      continue;
    }
    std::istringstream parts(value);
    std::string part;
    while (std::getline(parts, part, ',')) {
      if (!part.empty()) specs.push_back(part);
    }
  }
  args = rest;
  return specs;
}

int CheckSummary(const ArgParser& parser, const std::map<std::string, double>& tolerances);

}  // namespace

int CheckCommand(const Args& input_args) {
  ArgParser parser("check",
                   "Compare a summary.json with a baseline summary. Prints every checked metric "
                   "as baseline -> current with OK or WORSE and exits 1 when any metric got "
                   "worse by more than its tolerance (mean and median errors up, % <= "
                   "thresholds or AUC down, failed or flipped pairs up); exits 0 otherwise. "
                   "Timings are not checked. With --update, the baseline is rewritten with "
                   "SUMMARY (after printing the comparison) and the exit code is 0. A summary or "
                   "baseline that cannot be read, is malformed, or belongs to an unfinished run "
                   "exits 3.");
  parser.Positionals("SUMMARY", "summary.json of a run (or symembed eval)", 1, 1);
  parser.Option("baseline", "baseline summary file (e.g. results/baselines/synthetic.json)", "");
  parser.Option("tolerance", ToleranceHelp(), "");
  parser.Switch("update", "write SUMMARY to the baseline file");
  Args args = input_args;
  const std::vector<std::string> specs = TakeTolerances(args);
  if (!parser.Parse(args)) return 0;
  if (!parser.Given("baseline")) throw UsageError{"--baseline FILE is required"};
  std::map<std::string, double> tolerances;
  try {
    tolerances = ParseTolerances(specs);
  } catch (const ConfigError& e) {
    throw UsageError{e.what()};
  }
  try {
    return CheckSummary(parser, tolerances);
  } catch (const InvalidInputError& e) {
    std::cerr << "symembed check: error: " << e.what() << "\n";
    return kMalformedInput;
  } catch (const IoError& e) {
    std::cerr << "symembed check: error: " << e.what() << "\n";
    return kMalformedInput;
  }
}

namespace {

int CheckSummary(const ArgParser& parser, const std::map<std::string, double>& tolerances) {
  const std::string summary_path = parser.positionals()[0];
  const std::string baseline_path = parser.Get("baseline");
  RequireNotInProgress(std::filesystem::path(summary_path).parent_path().string());
  const std::string summary_text = ReadFileOrThrow(summary_path);
  const JsonValue current = ParseJson(summary_text, summary_path);
  ValidateSummary(current, summary_path);
  const bool update = parser.Flag("update");

  if (!std::filesystem::exists(baseline_path)) {
    if (!update) throw IoError(baseline_path + ": baseline not found (use --update to create it)");
    WriteFileAtomically(baseline_path, summary_text);
    std::cout << "check: created baseline " << baseline_path << "\n";
    return 0;
  }
  const JsonValue baseline = ParseJson(ReadFileOrThrow(baseline_path), baseline_path);
  ValidateSummary(baseline, baseline_path);
  const CheckResult result = CompareSummaries(baseline, current, tolerances);
  std::cout << "baseline " << baseline_path << " -> " << summary_path << "\n"
            << FormatCheck(result);
  if (update) {
    WriteFileAtomically(baseline_path, summary_text);
    std::cout << "check: baseline " << baseline_path << " updated\n";
    return 0;
  }
  return result.worse ? 1 : 0;
}

}  // namespace

}  // namespace symembed

// symembed report RESULTS_DIR [--out DIR]
#include <cstdio>
#include <iostream>

#include "apps/args.h"
#include "apps/commands.h"
#include "harness/html/html_report.h"
#include "registry/registry.h"

namespace symembed {

namespace {

// The warnings are often one cause repeated (a dataset folder missing for every pair): the
// first few are enough on the terminal; the page lists them all.
constexpr size_t kWarningsShown = 5;

void PrintReport(const std::string& command, const HtmlReportResult& r) {
  for (size_t i = 0; i < r.warnings.size() && i < kWarningsShown; ++i) {
    std::cerr << "symembed " << command << ": warning: " << r.warnings[i] << "\n";
  }
  if (r.warnings.size() > kWarningsShown) {
    std::cerr << "symembed " << command << ": ... and " << r.warnings.size() - kWarningsShown
              << " more warnings, listed on the report's page\n";
  }
  char size[32];
  std::snprintf(size, sizeof size, "%.1f MB", static_cast<double>(r.bytes) / 1e6);
  std::cout << "report: " << r.index_path << " (" << r.variants << " variants, " << r.shapes
            << " shapes, " << r.pairs_viewable << " pair views";
  if (r.pairs_unavailable > 0) std::cout << ", " << r.pairs_unavailable << " unavailable";
  std::cout << "; " << size << ")\n";
}

}  // namespace

void ReportAfterCommand(const std::string& command, const std::string& results_dir,
                        const Registry& registry) {
  try {
    PrintReport(command, WriteHtmlReport(results_dir, HtmlReportOptions(), registry));
  } catch (const std::exception& e) {
    std::cerr << "symembed " << command << ": warning: no HTML report: " << e.what() << "\n";
  }
}

int ReportCommand(const Args& args) {
  ArgParser parser(
      "report",
      "Write an HTML report of a results folder (an experiment folder of `symembed run` or "
      "`merge`, or the output folder of `symembed eval`): OUT/index.html with the summary "
      "table, curves, per-class and per-stage tables, every variant's pairs, and a 3D view of "
      "each pair's map (colour transfer, ground truth, error heat map). Open it from the file "
      "system in a browser; it needs no network. Meshes are read from the dataset of each "
      "variant's config.yaml, relative paths from the working directory (as the run did). A "
      "shape or map that cannot be read makes only its pairs unavailable (the reason is on the "
      "page). `symembed run`, `merge` and `eval` write it too unless given --no-report. "
      "Exit status: 0 when the report was written, 1 when not.");
  parser.Option("out", "report folder (replaced when it holds an earlier report)",
                "RESULTS_DIR/report");
  parser.Option("jobs", "worker threads (0: all cores)", "0");
  parser.Positionals("RESULTS_DIR", "the results folder", 1, 1);
  if (!parser.Parse(args)) return 0;
  HtmlReportOptions options;
  if (parser.Given("out")) options.out_dir = parser.Get("out");
  options.threads = parser.GetInt("jobs");
  if (options.threads < 0) throw UsageError{"--jobs: must be >= 0"};
  Registry registry;
  RegisterBuiltinStages(registry);
  PrintReport("report", WriteHtmlReport(parser.positionals()[0], options, registry));
  return 0;
}

}  // namespace symembed

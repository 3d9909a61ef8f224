// `symembed report`: an HTML report of a results folder, opened straight from the file system
// (file://) in a current browser, without network. Layout of the report folder:
//
//   index.html, report.css, *.js   the page (harness/html/assets/)
//   data.js              window.SYMEMBED_REPORT: every variant's summary.json, curve, pairs.csv
//                        rows with stage times, class and side file (as {columns, rows}),
//                        config.yaml text and its differences from the first variant's, the
//                        shapes and which side file holds each
//   shapes/NAME.js       one per shape: mesh and ground truth (harness/html/pair_views.h)
//   pairs/A_B-HASH.js    one per distinct map: the map and its per-point errors; variants whose
//                        maps of a pair are equal share the file
//
// The page loads side files on demand through <script> (a file:// page may not fetch). docs/
// report.md describes the page.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "registry/registry.h"

namespace symembed {

struct HtmlReportOptions {
  std::string out_dir;  // the report folder; empty: RESULTS_DIR/report
  int threads = 0;      // 0: DefaultThreadCount()
};

struct HtmlReportResult {
  std::string index_path;  // OUT/index.html
  int variants = 0;
  int shapes = 0;             // shape side files written
  int pair_files = 0;         // pair side files written (distinct maps)
  int pairs_viewable = 0;     // pair rows (all variants) whose 3D view has its data
  int pairs_unavailable = 0;  // successful pairs whose view could not be built
  int64_t bytes = 0;          // size of the report folder
  // Variants left out, datasets that could not be opened, shapes and pairs whose view could
  // not be built: each names the file and the reason (also shown on the page).
  std::vector<std::string> warnings;
};

// Writes the report of results_dir (an experiment folder or one variant / `symembed eval`
// folder; FindReportVariants). Meshes are read from the dataset of each variant's config.yaml
// (or of eval.json), relative paths from the working directory, as the run did. The report is
// written to a sibling temporary folder, then replaces OUT (only when OUT is empty or holds a
// report: an index.html). A missing mesh or map, or a malformed one, makes its shapes or pairs
// unavailable (reason on the page and in warnings), never the whole report. Throws IoError
// naming the path when results_dir holds no finished variant or OUT cannot be written.
HtmlReportResult WriteHtmlReport(const std::string& results_dir, const HtmlReportOptions& options,
                                 const Registry& registry);

}  // namespace symembed

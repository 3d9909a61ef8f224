// The outputs of a run folder without timings, for comparing runs byte for byte: skips
// timings.csv, the shape records, plots and the HTML report (report/: built from the rest); drops the time_* and peak_rss_mb keys of
// summary.json, the time and memory columns of comparison.csv and the stage times of the
// per-pair records. Header-only (tests/ compiles only *_test.cpp and test_util.cpp).
#pragma once

#include <filesystem>
#include <map>
#include <sstream>
#include <string>

#include "eval/report.h"
#include "tests/test_util.h"

namespace symembed::testing {

inline std::map<std::string, std::string> OutputsWithoutTimings(const std::string& dir) {
  namespace fs = std::filesystem;
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string rel = fs::relative(e.path(), dir).string();
    const std::string name = e.path().filename().string();
    const std::string ext = e.path().extension().string();
    if (name == "timings.csv" || rel.find("shapes/") != std::string::npos ||
        rel.rfind("report/", 0) == 0 ||
        name.find(".tmp.") != std::string::npos || ext == ".png" || ext == ".svg") {
      continue;
    }
    std::string text = ReadText(e.path().string());
    if (ext == ".rec") {
      PairEvaluation pair = ParsePairRecord(text, rel);
      pair.stage_seconds.clear();
      text = SerializePairRecord(pair);
    } else if (name == "summary.json" || name == "comparison.csv") {
      std::istringstream in(text);
      std::string kept;
      for (std::string line; std::getline(in, line);) {
        if (name == "summary.json" && (line.find("\"time_") != std::string::npos ||
                                       line.find("\"peak_rss_mb\"") != std::string::npos)) {
          continue;
        }
        if (name == "comparison.csv") {
          // time_total_s, time_per_shape_s, time_per_pair_s, peak_rss_mb are the last four.
          for (int drop = 0; drop < 4; ++drop) line = line.substr(0, line.rfind(','));
        }
        kept += line + "\n";
      }
      text = kept;
    }
    files[rel] = text;
  }
  return files;
}

}  // namespace symembed::testing

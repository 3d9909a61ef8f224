// The numbers of the HTML report (harness/html/html_report.h), read from a results folder as
// `symembed run`, `merge` and `eval` leave it: summary.json, curve.csv, pairs.csv, timings.csv
// and config.yaml of each variant. Nothing is recomputed: the report shows what the run wrote.
#pragma once

#include <string>
#include <vector>

#include "eval/json.h"

namespace symembed {

struct ReportVariant {
  std::string name;  // the variant ("base", ...; summary.json's "variant" for a single folder)
  std::string dir;   // its folder (summary.json, pairs.csv, ...)
};

// The variants of results_dir, in order: an experiment folder (variants.txt; a listed variant
// without summary.json is left out, with a warning when its folder exists: still running or
// interrupted) or a single variant or `symembed eval` folder (summary.json). Throws IoError naming the path when
// results_dir does not exist, holds neither, or none of its variants has a summary.json yet.
std::vector<ReportVariant> FindReportVariants(const std::string& results_dir,
                                              std::vector<std::string>* warnings);

// One variant's data for the page:
//   name, summary      summary.json as written (same keys and numbers)
//   config             config.yaml text, or null (a `symembed eval` folder has none)
//   curve              {threshold, direct, flip_tolerant}: the columns of curve.csv
//   pairs              one object per pairs.csv row: its columns under their header names
//                      (numbers as numbers, empty or nan as null, candidate_errors an array),
//                      plus "seconds": {stage: seconds} from timings.csv
//   stage_seconds      {"shape": {stage: mean}, "pair": {stage: mean}} over timings.csv rows
// Throws InvalidInputError or IoError naming the file that is missing or malformed.
JsonValue VariantReportData(const ReportVariant& variant);

// The settings in which two config.yaml texts differ, one "dotted.path: a -> b" per leaf
// (a or b "(none)" when only one side has it), sorted by path. Throws InvalidInputError
// naming `where` when a text is not YAML.
std::vector<std::string> ConfigDifferences(const std::string& base_yaml,
                                           const std::string& variant_yaml,
                                           const std::string& where);

}  // namespace symembed

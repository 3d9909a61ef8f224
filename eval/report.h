// Result files of an evaluation.
//
// Per variant directory:
//   summary.json  VariantSummary (keys below; numbers exact, NaN as null)
//   pairs.csv     one row per pair, sorted by (source, target); no timing columns
//   curve.csv     threshold, direct, flip_tolerant (fractions of points with error <= t)
//   timings.csv   kind (shape|pair|variant), name, stage, seconds; a pair's name is its file
//                 stem among the pairs of pairs.csv (eval/pair_names.h: "A_B" unless
//                 ambiguous)
// Per experiment directory:
//   comparison.csv  one row per variant, the summary's numbers
//   curves.png / curves.svg  from scripts/plot-curves (needs /usr/bin/python3 + matplotlib)
// Everything except timings.csv and the time_* / peak_rss_mb keys of summary.json depends only
// on the set of per-pair records, so sharded runs merged reproduce a single run byte for byte.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "eval/json.h"
#include "eval/metrics.h"

namespace symembed {

// One value of summary.json, in the file's order: its key ("mean_direct", or "group.key" for a
// member of an object, e.g. "pct_direct.0.05", "flipped_pairs.total"), its comparison.csv
// column (empty: not in comparison.csv), and how it is written, read back and printed. Read:
// kRequired (missing or of the wrong type fails), kOptional (a default when absent), kWritten
// (derived, never read). to_json returns null for a value not written (shapes_lost_area of an
// eval). check: whether `symembed check` compares the value with a baseline's
// (eval/baseline.h), which way is better and the default absolute tolerance. Adding a value to
// the summary, to comparison.csv or to the check is one entry of SummaryEntries().
struct SummaryEntry {
  enum class Read { kRequired, kOptional, kWritten };
  struct Check {
    bool higher_is_better = false;
    double tolerance = 0.0;
  };
  std::string key;
  std::string csv_column;
  Read read = Read::kOptional;
  std::optional<Check> check;
  std::function<JsonValue(const VariantSummary&)> to_json;
  // value: the key's value (null when absent); present: whether the key was there; key, where:
  // for messages.
  std::function<void(VariantSummary&, const JsonValue& value, bool present,
                     const std::string& key, const std::string& where)>
      from_json;
  std::function<std::string(const VariantSummary&)> csv_cell;
};
const std::vector<SummaryEntry>& SummaryEntries();

// summary.json: pairs, failed_pairs, points, mean_direct, median_direct, mean_flip_tolerant,
// median_flip_tolerant, mean_of_pair_means_direct, mean_of_pair_means_flip_tolerant,
// pct_direct / pct_flip_tolerant ({"0.05", "0.10", "0.25"}: percent), auc_direct,
// auc_flip_tolerant, flipped_pairs {left_right, front_back, up_down, total}, refine_changed_side
// {to_symmetric, to_direct}, shapes_lost_area (runs only: shapes whose preprocessing removed
// components),
// evaluation_geodesics, evaluation_points ("all" or N), max_error, step, variant, then the
// timing keys time_total_s, time_per_shape_s, time_per_pair_s, peak_rss_mb.
JsonValue SummaryToJson(const VariantSummary& summary);
// Reads the keys above back (curves are not in summary.json and stay empty).
// Throws InvalidInputError naming `where` for a missing key or wrong type.
VariantSummary SummaryFromJson(const JsonValue& json, const std::string& where = "summary");
void WriteSummaryJson(const std::string& path, const VariantSummary& summary);
VariantSummary ReadSummaryJson(const std::string& path);

// One column of pairs.csv: its name, what its cells hold, and the cell of one pair (CSV-escaped;
// empty where the pair has no value, e.g. errors of a failed pair).
struct PairsCsvColumn {
  enum class Kind { kText, kNumber, kNumberList };  // a number list is space-separated
  std::string name;
  Kind kind = Kind::kNumber;
  std::function<std::string(const PairEvaluation&)> cell;
};

// The columns of pairs.csv, in order: source, target, status, points, mean_direct,
// median_direct, max_direct, pct_direct_<threshold> per ErrorThresholdKeys(), mean_sym,
// mean_flip_tolerant, flip, chosen, oracle, initial_mean_direct, refine_side, candidate_errors,
// flip_message, refine_message, message.
const std::vector<PairsCsvColumn>& PairsCsvColumns();

// A CSV field as every CSV file of a run writes it (RFC 4180): quoted, with its quotes doubled,
// when it holds a comma, a quote or a line break; else as it is.
std::string CsvField(const std::string& text);

// File contents (deterministic; pairs are sorted by (source, target)).
std::string PairsCsv(std::vector<PairEvaluation> pairs);
std::string CurveCsv(const VariantSummary& summary);
std::string TimingsCsv(std::vector<PairEvaluation> pairs, const VariantTimings& timings);
std::string ComparisonCsv(const std::vector<VariantSummary>& variants);

// Writes summary.json, pairs.csv, curve.csv, timings.csv into dir (created when missing),
// each atomically. Throws IoError.
void WriteVariantOutputs(const std::string& dir, const VariantSummary& summary,
                         const std::vector<PairEvaluation>& pairs, const VariantTimings& timings);

// Writes comparison.csv into the experiment directory, atomically, then runs
// scripts/plot-curves on it when available. Returns false and sets *warning when the plot
// could not be made (never an error: the CSVs are the source of truth).
bool WriteComparison(const std::string& experiment_dir, const std::vector<VariantSummary>& variants,
                     std::string* warning);

// Runs `/usr/bin/python3 scripts/plot-curves DIR` (DIR: an experiment directory with
// VARIANT/curve.csv, or a variant directory with curve.csv) and waits for it; the helper is
// killed when this process dies. The script is found through
// $SYMEMBED_ROOT, else by walking up from the executable. Returns false and sets *warning
// when the script, python3 or matplotlib is missing, or the script fails.
bool PlotCurves(const std::string& dir, std::string* warning);

// One pair as a one-line JSON record with its error vectors, stage times and flip (one row of
// RecordMembers() in report.cpp per member); parsing it gives back an equal PairEvaluation
// (every double exact). The inputs, when the pair has them, are the first member, written
// without spaces:
// {"inputs":{"source":"<16 hex>","target":"<16 hex>","pair":"<16 hex>"},"source": ...
// Parsing throws InvalidInputError naming `where`, also for an `inputs` member of another form.
std::string SerializePairRecord(const PairEvaluation& pair);
PairEvaluation ParsePairRecord(const std::string& text, const std::string& where = "record");

}  // namespace symembed

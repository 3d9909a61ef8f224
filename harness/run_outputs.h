// Small text files the runner writes beside the evaluator's outputs, and reads back on
// --resume and in `symembed merge`:
//   failures.csv       kind,source,target,message   (kind: shape | pair; target empty for a
//                      shape); sorted, no duplicates, so shards merged equal a single run
//   shapes/NAME.rec    per shape: "time<TAB>stage<TAB>seconds<TAB>cached" and
//                      "report<TAB>name<TAB>value" lines
//   shapes.csv         one row per shape record: shape, then every report entry (columns in
//                      order of first appearance; empty where a shape lacks one)
//   variants.txt       in the experiment folder: the config's variant names, in order
#pragma once

#include <string>
#include <vector>

#include "harness/shape_pipeline.h"

namespace symembed {

struct Failure {
  std::string kind;    // "shape" or "pair"
  std::string source;  // the shape, or the pair's source
  std::string target;  // the pair's target; empty for a shape
  std::string message;
  bool operator<(const Failure& other) const;
  bool operator==(const Failure& other) const;
};

// Splits CSV text (RFC 4180: quoted fields may hold commas, quotes and newlines) into records of
// fields, the header included. Throws InvalidInputError naming `where` and the line.
std::vector<std::vector<std::string>> ParseCsv(const std::string& text, const std::string& where);

// Sorted and de-duplicated CSV (RFC 4180 quoting) with a header line.
std::string FailuresCsv(std::vector<Failure> failures);
// Throws InvalidInputError naming `where` and the line.
std::vector<Failure> ParseFailuresCsv(const std::string& text, const std::string& where);

struct ShapeRecord {
  std::string name;
  std::vector<StageTime> times;
  Report report;
};

std::string FormatShapeRecord(const ShapeRecord& record);
// Throws InvalidInputError naming `where` and the line.
ShapeRecord ParseShapeRecord(const std::string& name, const std::string& text,
                             const std::string& where);

// The shapes.csv table of the records' report entries.
std::string ShapesCsv(const std::vector<ShapeRecord>& shapes);

// The layout of an experiment's output folder OUT: OUT/variants.txt, and per variant folder
// OUT/<variant>/ its config.yaml, maps/STEM.map, pairs/STEM.rec and shapes/NAME.rec (besides
// failures.csv, shapes.csv and the evaluation's summary files). STEM: the pair's stem among the
// variant's pairs (eval/pair_names.h), "A_B" unless that is ambiguous.
std::string VariantsListPath(const std::string& out_dir);
std::string VariantConfigPath(const std::string& variant_dir);
std::string PairMapPath(const std::string& variant_dir, const std::string& stem);
std::string PairRecordPath(const std::string& variant_dir, const std::string& stem);
std::string ShapeRecordPath(const std::string& variant_dir, const std::string& shape);

// The variant names of a variants.txt, in order (empty lines skipped).
std::vector<std::string> ParseVariantsList(const std::string& text);

// A folder being written (a variant of `symembed run`, a merge, an eval) holds IN_PROGRESS until
// its summary is complete; readers of results refuse such a folder.
std::string InProgressPath(const std::string& dir);
// Writes the marker (saying `what` is writing the folder) and creates the folder. Throws IoError.
void MarkInProgress(const std::string& dir, const std::string& what);
void ClearInProgress(const std::string& dir);
// Throws InvalidInputError naming the folder when it holds the marker.
void RequireNotInProgress(const std::string& dir);

}  // namespace symembed

#include "harness/html/report_data.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>

#include "core/errors.h"
#include "core/files.h"
#include "eval/pair_names.h"
#include "eval/report.h"
#include "harness/run_outputs.h"

namespace symembed {

namespace fs = std::filesystem;

namespace {

// What a column of pairs.csv holds (text columns stay text even where they look like numbers,
// as shape names may); a column this version does not write reads as numbers.
PairsCsvColumn::Kind ColumnKind(const std::string& name) {
  for (const auto& column : PairsCsvColumns()) {
    if (column.name == name) return column.kind;
  }
  return PairsCsvColumn::Kind::kNumber;
}

// A CSV field as JSON: null when empty or nan, a number when the whole field is one, else text.
JsonValue FieldValue(const std::string& text) {
  if (text.empty() || text == "nan") return JsonValue();
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  if (end == text.c_str() + text.size() && std::isfinite(x)) return JsonValue::Number(x);
  return JsonValue::String(text);
}

JsonValue NumberList(const std::string& text) {
  JsonValue a = JsonValue::Array();
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find(' ', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) a.Push(FieldValue(text.substr(start, end - start)));
    start = end + 1;
  }
  return a;
}

// The rows of a CSV file with a header, each as header -> field.
std::vector<std::map<std::string, std::string>> ReadCsvTable(const std::string& path) {
  const auto rows = ParseCsv(ReadFileOrThrow(path), path);
  if (rows.empty()) throw InvalidInputError(path + ": empty file (no header line)");
  std::vector<std::map<std::string, std::string>> table;
  for (size_t r = 1; r < rows.size(); ++r) {
    if (rows[r].size() != rows[0].size()) {
      throw InvalidInputError(path + ":" + std::to_string(r + 1) + ": " +
                              std::to_string(rows[r].size()) + " fields, the header has " +
                              std::to_string(rows[0].size()));
    }
    std::map<std::string, std::string> row;
    for (size_t c = 0; c < rows[0].size(); ++c) row[rows[0][c]] = rows[r][c];
    table.push_back(std::move(row));
  }
  return table;
}

const std::string& Field(const std::map<std::string, std::string>& row, const std::string& column,
                         const std::string& path) {
  const auto it = row.find(column);
  if (it == row.end()) throw InvalidInputError(path + ": no column '" + column + "'");
  return it->second;
}

JsonValue CurveData(const std::string& path) {
  JsonValue threshold = JsonValue::Array(), direct = JsonValue::Array(),
            tolerant = JsonValue::Array();
  for (const auto& row : ReadCsvTable(path)) {
    threshold.Push(FieldValue(Field(row, "threshold", path)));
    direct.Push(FieldValue(Field(row, "direct", path)));
    tolerant.Push(FieldValue(Field(row, "flip_tolerant", path)));
  }
  JsonValue curve = JsonValue::Object();
  curve.Set("threshold", threshold);
  curve.Set("direct", direct);
  curve.Set("flip_tolerant", tolerant);
  return curve;
}

// timings.csv: per pair name (its file stem, eval/pair_names.h) its stage seconds, and the
// mean per stage of shapes and pairs.
struct Timings {
  std::map<std::string, JsonValue> pair_seconds;
  JsonValue means = JsonValue::Object();
};

Timings ReadTimings(const std::string& path) {
  Timings t;
  std::map<std::string, std::map<std::string, std::pair<double, int>>> sums;  // kind, stage
  for (const auto& row : ReadCsvTable(path)) {
    const std::string& kind = Field(row, "kind", path);
    const std::string& name = Field(row, "name", path);
    const std::string& stage = Field(row, "stage", path);
    const JsonValue seconds = FieldValue(Field(row, "seconds", path));
    if (kind == "pair") {
      auto [it, added] = t.pair_seconds.emplace(name, JsonValue::Object());
      it->second.Set(stage, seconds);
    }
    if ((kind == "pair" || kind == "shape") && seconds.IsNumber()) {
      auto& sum = sums[kind][stage];
      sum.first += seconds.AsNumber();
      sum.second += 1;
    }
  }
  for (const char* kind : {"shape", "pair"}) {
    JsonValue stages = JsonValue::Object();
    for (const auto& [stage, sum] : sums[kind]) {
      stages.Set(stage, JsonValue::Number(sum.first / sum.second));
    }
    t.means.Set(kind, stages);
  }
  return t;
}

JsonValue PairRows(const std::string& path, const Timings& timings) {
  const auto rows = ReadCsvTable(path);
  // timings.csv names each pair among the rows of pairs.csv, which it was written with.
  std::vector<DatasetPair> listed;
  for (const auto& row : rows) {
    listed.push_back({Field(row, "source", path), Field(row, "target", path)});
  }
  const PairNames names(listed);
  JsonValue pairs = JsonValue::Array();
  for (const auto& row : rows) {
    JsonValue pair = JsonValue::Object();
    for (const auto& [column, text] : row) {
      switch (ColumnKind(column)) {
        case PairsCsvColumn::Kind::kNumberList:
          pair.Set(column, NumberList(text));
          break;
        case PairsCsvColumn::Kind::kText:
          pair.Set(column, JsonValue::String(text));
          break;
        case PairsCsvColumn::Kind::kNumber:
          pair.Set(column, FieldValue(text));
          break;
      }
    }
    const auto it = timings.pair_seconds.find(
        names.Stem(Field(row, "source", path), Field(row, "target", path)));
    pair.Set("seconds", it == timings.pair_seconds.end() ? JsonValue::Object() : it->second);
    pairs.Push(pair);
  }
  return pairs;
}

// Leaves of a YAML tree as dotted path -> scalar text (sequences as their flow text).
void Flatten(const YAML::Node& node, const std::string& path,
             std::map<std::string, std::string>* leaves) {
  if (node.IsMap()) {
    for (const auto& item : node) {
      const std::string key = item.first.as<std::string>();
      Flatten(item.second, path.empty() ? key : path + "." + key, leaves);
    }
    return;
  }
  YAML::Emitter out;
  out << YAML::Flow << node;
  (*leaves)[path] = out.c_str();
}

std::map<std::string, std::string> FlattenYaml(const std::string& text, const std::string& where) {
  std::map<std::string, std::string> leaves;
  try {
    Flatten(YAML::Load(text), "", &leaves);
  } catch (const YAML::Exception& e) {
    throw InvalidInputError(where + ": " + e.what());
  }
  return leaves;
}

}  // namespace

std::vector<ReportVariant> FindReportVariants(const std::string& results_dir,
                                              std::vector<std::string>* warnings) {
  if (!fs::is_directory(results_dir)) {
    throw IoError(results_dir + ": no such results folder");
  }
  const std::string list = VariantsListPath(results_dir);
  std::vector<ReportVariant> variants;
  if (fs::exists(list)) {
    for (const std::string& name : ParseVariantsList(ReadFileOrThrow(list))) {
      const std::string dir = (fs::path(results_dir) / name).string();
      if (fs::exists(dir + "/summary.json") && !fs::exists(InProgressPath(dir))) {
        variants.push_back({name, dir});
      } else if (warnings && fs::exists(dir)) {
        // A variant without a folder was not run (--variant), which is no news.
        warnings->push_back(dir +
                            "/summary.json: missing (the variant is still running or was "
                            "interrupted); left out of the report");
      }
    }
    if (variants.empty()) {
      throw IoError(results_dir + ": no variant listed in " + list +
                    " has a summary.json yet (the run is in progress or was interrupted; "
                    "finish it with symembed run --resume)");
    }
    return variants;
  }
  const std::string summary = results_dir + "/summary.json";
  RequireNotInProgress(results_dir);
  if (fs::exists(summary)) {
    // The variant's own name (symembed eval's --name), else the folder's.
    const JsonValue variant = ParseJson(ReadFileOrThrow(summary), summary).Get("variant");
    std::string name = variant.IsString() ? variant.AsString() : "";
    if (name.empty()) name = fs::absolute(results_dir).lexically_normal().filename().string();
    if (name.empty()) {
      name = fs::absolute(results_dir).lexically_normal().parent_path().filename().string();
    }
    return {{name, results_dir}};
  }
  throw IoError(results_dir +
                ": not a results folder (no variants.txt and no summary.json; "
                "a run that has just started writes them at its end)");
}

JsonValue VariantReportData(const ReportVariant& variant) {
  const std::string dir = variant.dir;
  JsonValue data = JsonValue::Object();
  data.Set("name", JsonValue::String(variant.name));
  const std::string summary_path = dir + "/summary.json";
  data.Set("summary", ParseJson(ReadFileOrThrow(summary_path), summary_path));
  const auto config = ReadFileBytes(VariantConfigPath(dir));
  data.Set("config", config ? JsonValue::String(*config) : JsonValue());
  data.Set("curve", CurveData(dir + "/curve.csv"));
  Timings timings;
  if (fs::exists(dir + "/timings.csv")) timings = ReadTimings(dir + "/timings.csv");
  data.Set("pairs", PairRows(dir + "/pairs.csv", timings));
  data.Set("stage_seconds", timings.means);
  return data;
}

std::vector<std::string> ConfigDifferences(const std::string& base_yaml,
                                           const std::string& variant_yaml,
                                           const std::string& where) {
  const auto a = FlattenYaml(base_yaml, where);
  const auto b = FlattenYaml(variant_yaml, where);
  std::set<std::string> paths;
  for (const auto& [path, value] : a) paths.insert(path);
  for (const auto& [path, value] : b) paths.insert(path);
  std::vector<std::string> differences;
  for (const std::string& path : paths) {
    const auto ia = a.find(path);
    const auto ib = b.find(path);
    const std::string va = ia == a.end() ? "(none)" : ia->second;
    const std::string vb = ib == b.end() ? "(none)" : ib->second;
    if (va != vb) differences.push_back(path + ": " + va + " -> " + vb);
  }
  return differences;
}

}  // namespace symembed

#include "harness/run_outputs.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <tuple>

#include "core/errors.h"
#include "core/files.h"
#include "eval/report.h"

namespace symembed {

std::vector<std::vector<std::string>> ParseCsv(const std::string& text, const std::string& where) {
  std::vector<std::vector<std::string>> rows;
  std::vector<std::string> row;
  std::string field;
  bool quoted = false, in_quotes = false, any = false;
  int line = 1;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        in_quotes = false;
      } else {
        if (c == '\n') ++line;
        field += c;
      }
      continue;
    }
    if (c == '"' && field.empty() && !quoted) {
      in_quotes = quoted = any = true;
    } else if (c == ',') {
      row.push_back(field);
      field.clear();
      quoted = false;
    } else if (c == '\n') {
      row.push_back(field);
      rows.push_back(row);
      row.clear();
      field.clear();
      quoted = any = false;
      ++line;
    } else if (c != '\r') {
      if (quoted)
        throw InvalidInputError(where + ":" + std::to_string(line) + ": text after a quoted field");
      field += c;
      any = true;
    }
  }
  if (in_quotes)
    throw InvalidInputError(where + ":" + std::to_string(line) + ": unterminated quote");
  if (any || !row.empty()) {
    row.push_back(field);
    rows.push_back(row);
  }
  return rows;
}

bool Failure::operator<(const Failure& o) const {
  return std::tie(kind, source, target, message) < std::tie(o.kind, o.source, o.target, o.message);
}

bool Failure::operator==(const Failure& o) const {
  return std::tie(kind, source, target, message) == std::tie(o.kind, o.source, o.target, o.message);
}

std::string FailuresCsv(std::vector<Failure> failures) {
  std::sort(failures.begin(), failures.end());
  failures.erase(std::unique(failures.begin(), failures.end()), failures.end());
  std::string out = "kind,source,target,message\n";
  for (const Failure& f : failures) {
    out += CsvField(f.kind) + "," + CsvField(f.source) + "," + CsvField(f.target) + "," +
           CsvField(f.message) + "\n";
  }
  return out;
}

std::vector<Failure> ParseFailuresCsv(const std::string& text, const std::string& where) {
  const auto rows = ParseCsv(text, where);
  if (rows.empty() || rows[0] != std::vector<std::string>{"kind", "source", "target", "message"}) {
    throw InvalidInputError(where + ":1: expected the header kind,source,target,message");
  }
  std::vector<Failure> out;
  for (size_t i = 1; i < rows.size(); ++i) {
    if (rows[i].size() != 4 || (rows[i][0] != "shape" && rows[i][0] != "pair")) {
      throw InvalidInputError(where + ": record " + std::to_string(i + 1) +
                              ": expected kind (shape|pair),source,target,message");
    }
    out.push_back({rows[i][0], rows[i][1], rows[i][2], rows[i][3]});
  }
  return out;
}

std::string ShapesCsv(const std::vector<ShapeRecord>& shapes) {
  std::vector<std::string> columns;
  for (const ShapeRecord& shape : shapes) {
    for (const auto& entry : shape.report) {
      if (std::find(columns.begin(), columns.end(), entry.first) == columns.end()) {
        columns.push_back(entry.first);
      }
    }
  }
  std::string out = "shape";
  for (const std::string& c : columns) out += "," + CsvField(c);
  out += "\n";
  char number[64];
  for (const ShapeRecord& shape : shapes) {
    out += CsvField(shape.name);
    for (const std::string& c : columns) {
      out += ",";
      for (const auto& [name, value] : shape.report) {
        if (name != c) continue;
        std::snprintf(number, sizeof number, "%.9g", value);
        out += number;
        break;
      }
    }
    out += "\n";
  }
  return out;
}

std::string FormatShapeRecord(const ShapeRecord& record) {
  std::ostringstream out;
  char number[64];
  for (const StageTime& t : record.times) {
    std::snprintf(number, sizeof number, "%.17g", t.seconds);
    out << "time\t" << t.stage << "\t" << number << "\t" << (t.cached ? 1 : 0) << "\n";
  }
  for (const auto& [name, value] : record.report) {
    std::snprintf(number, sizeof number, "%.17g", value);
    out << "report\t" << name << "\t" << number << "\n";
  }
  return out.str();
}

ShapeRecord ParseShapeRecord(const std::string& name, const std::string& text,
                             const std::string& where) {
  ShapeRecord record;
  record.name = name;
  std::istringstream in(text);
  std::string line;
  int line_number = 0;
  while (std::getline(in, line)) {
    ++line_number;
    if (line.empty()) continue;
    std::vector<std::string> fields;
    std::string field;
    std::istringstream line_stream(line);
    while (std::getline(line_stream, field, '\t')) fields.push_back(field);
    try {
      if (fields.size() == 4 && fields[0] == "time") {
        record.times.push_back({fields[1], std::stod(fields[2]), fields[3] == "1"});
        continue;
      }
      if (fields.size() == 3 && fields[0] == "report") {
        record.report.emplace_back(fields[1], std::stod(fields[2]));
        continue;
      }
    } catch (const std::exception&) {
    }
    throw InvalidInputError(where + ":" + std::to_string(line_number) +
                            ": expected 'time<TAB>stage<TAB>seconds<TAB>cached' or "
                            "'report<TAB>name<TAB>value'");
  }
  return record;
}

std::string VariantsListPath(const std::string& out_dir) { return out_dir + "/variants.txt"; }

std::string VariantConfigPath(const std::string& variant_dir) {
  return variant_dir + "/config.yaml";
}

std::string PairMapPath(const std::string& variant_dir, const std::string& stem) {
  return variant_dir + "/maps/" + stem + ".map";
}

std::string PairRecordPath(const std::string& variant_dir, const std::string& stem) {
  return variant_dir + "/pairs/" + stem + ".rec";
}

std::string ShapeRecordPath(const std::string& variant_dir, const std::string& shape) {
  return variant_dir + "/shapes/" + shape + ".rec";
}

std::vector<std::string> ParseVariantsList(const std::string& text) {
  std::vector<std::string> lines;
  size_t start = 0;
  while (start < text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    if (end > start) lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

std::string InProgressPath(const std::string& dir) { return dir + "/IN_PROGRESS"; }

void MarkInProgress(const std::string& dir, const std::string& what) {
  WriteFileAtomically(InProgressPath(dir),
                      what + " is writing this folder; its outputs are incomplete until it "
                             "finishes and removes this file\n");
}

void ClearInProgress(const std::string& dir) {
  std::error_code ec;
  std::filesystem::remove(InProgressPath(dir), ec);
}

void RequireNotInProgress(const std::string& dir) {
  if (std::filesystem::exists(InProgressPath(dir))) {
    throw InvalidInputError(dir + ": the folder is incomplete (IN_PROGRESS: a run, merge or eval "
                                  "was interrupted or is still writing it); finish it with "
                                  "'symembed run ... --resume' or run it again");
  }
}

}  // namespace symembed

#include "eval/report.h"

#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <optional>
#include <sstream>
#include <type_traits>

#include "core/errors.h"
#include "core/files.h"
#include "eval/pair_names.h"
#include "registry/hash.h"

namespace fs = std::filesystem;

namespace symembed {

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();

// Fixed 8 significant digits in the CSV files (they are for reading and plotting; the exact
// values live in the per-pair records and summary.json).
std::string Num(double x) {
  if (std::isnan(x)) return "nan";
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.8g", x);
  return buffer;
}

const JsonValue& Require(const JsonValue& json, const std::string& key, const std::string& where) {
  if (!json.Has(key)) throw InvalidInputError(where + ": missing key '" + key + "'");
  return json.Get(key);
}

// The number `v`, the value of `key` (null: NaN); anything else fails.
double NumberOf(const JsonValue& v, const std::string& key, const std::string& where) {
  if (!v.IsNumber() && !v.IsNull()) {
    throw InvalidInputError(where + ": key '" + key + "' must be a number");
  }
  return v.NumberOr(kNaN);
}

double RequireNumber(const JsonValue& json, const std::string& key, const std::string& where) {
  return NumberOf(Require(json, key, where), key, where);
}

JsonValue NumberArray(const std::vector<double>& x) {
  JsonValue a = JsonValue::Array();
  for (double v : x) a.Push(JsonValue::Number(v));
  return a;
}

std::vector<double> ReadNumberArray(const JsonValue& a, const std::string& where) {
  if (!a.IsArray()) throw InvalidInputError(where + ": expected an array");
  std::vector<double> x;
  x.reserve(a.items().size());
  for (const auto& v : a.items()) x.push_back(v.NumberOr(kNaN));
  return x;
}

}  // namespace

std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string out = "\"";
  for (char c : text) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

namespace {

using Entry = SummaryEntry;

// A number of the summary: written as a JSON number; read back as RequireNumber reads it
// (kRequired) or as the number found, else `missing` (kOptional); in comparison.csv as Num, or
// as an integer for `integer` members.
template <typename T>
Entry NumberEntry(std::string key, T VariantSummary::*member, std::string csv_column,
                  Entry::Read read, double missing = kNaN) {
  Entry e;
  e.key = std::move(key);
  e.csv_column = std::move(csv_column);
  e.read = read;
  e.to_json = [member](const VariantSummary& s) {
    return JsonValue::Number(static_cast<double>(s.*member));
  };
  e.from_json = [member, read, missing](VariantSummary& s, const JsonValue& value, bool present,
                                        const std::string& key, const std::string& where) {
    double x = missing;
    if (read == Entry::Read::kRequired) {
      x = NumberOf(value, key, where);
    } else if (present) {
      x = value.NumberOr(missing);
    }
    s.*member = static_cast<T>(x);
  };
  if (e.csv_column.empty()) return e;
  e.csv_cell = [member](const VariantSummary& s) {
    if constexpr (std::is_integral_v<T>) {
      return std::to_string(s.*member);
    } else {
      return Num(s.*member);
    }
  };
  return e;
}

// One threshold of a thresholded percentage (pct_direct, pct_flip_tolerant): required.
Entry ThresholdEntry(const std::string& group, std::array<double, 3> VariantSummary::*member,
                     size_t k) {
  Entry e;
  e.key = group + "." + ErrorThresholdKeys()[k];
  e.csv_column = group + "_" + ErrorThresholdKeys()[k];
  e.read = Entry::Read::kRequired;
  e.to_json = [member, k](const VariantSummary& s) { return JsonValue::Number((s.*member)[k]); };
  e.from_json = [member, k](VariantSummary& s, const JsonValue& value, bool,
                            const std::string& key, const std::string& where) {
    (s.*member)[k] = NumberOf(value, key, where);
  };
  e.csv_cell = [member, k](const VariantSummary& s) { return Num((s.*member)[k]); };
  return e;
}

// The entry with the regression check of `symembed check`.
Entry Checked(Entry e, bool higher_is_better, double tolerance) {
  e.check = Entry::Check{higher_is_better, tolerance};
  return e;
}

std::vector<Entry> MakeSummaryEntries() {
  using Read = Entry::Read;
  using S = VariantSummary;
  constexpr bool kHigher = true, kLower = false;  // which way a checked value is better
  std::vector<Entry> t;
  {
    Entry e;  // the variant's name: optional when read (an eval of one variant may lack it)
    e.key = "variant";
    e.csv_column = "variant";
    e.read = Read::kOptional;
    e.to_json = [](const S& s) { return JsonValue::String(s.variant); };
    e.from_json = [](S& s, const JsonValue& v, bool, const std::string&, const std::string&) {
      if (v.IsString()) s.variant = v.AsString();
    };
    e.csv_cell = [](const S& s) { return CsvField(s.variant); };
    t.push_back(e);
  }
  t.push_back(NumberEntry("pairs", &S::pairs, "pairs", Read::kRequired));
  t.push_back(
      Checked(NumberEntry("failed_pairs", &S::failed_pairs, "failed_pairs", Read::kRequired),
              kLower, 0.0));
  t.push_back(NumberEntry("points", &S::total_points, "", Read::kOptional, 0.0));
  // Errors: of sqrt(area).
  t.push_back(Checked(NumberEntry("mean_direct", &S::mean_direct, "mean_direct", Read::kRequired),
                      kLower, 0.002));
  t.push_back(
      Checked(NumberEntry("median_direct", &S::median_direct, "median_direct", Read::kRequired),
              kLower, 0.002));
  t.push_back(Checked(NumberEntry("mean_flip_tolerant", &S::mean_flip_tolerant,
                                  "mean_flip_tolerant", Read::kRequired),
                      kLower, 0.002));
  t.push_back(NumberEntry("median_flip_tolerant", &S::median_flip_tolerant, "", Read::kOptional));
  t.push_back(NumberEntry("mean_of_pair_means_direct", &S::mean_of_pair_means_direct, "",
                          Read::kOptional));
  t.push_back(NumberEntry("mean_of_pair_means_flip_tolerant",
                          &S::mean_of_pair_means_flip_tolerant, "", Read::kOptional));
  // Percentages: percentage points.
  for (size_t k = 0; k < 3; ++k) {
    t.push_back(Checked(ThresholdEntry("pct_direct", &S::pct_direct, k), kHigher, 1.0));
  }
  for (size_t k = 0; k < 3; ++k) {
    t.push_back(
        Checked(ThresholdEntry("pct_flip_tolerant", &S::pct_flip_tolerant, k), kHigher, 1.0));
  }
  t.push_back(Checked(NumberEntry("auc_direct", &S::auc_direct, "auc_direct", Read::kRequired),
                      kHigher, 0.005));
  t.push_back(NumberEntry("auc_flip_tolerant", &S::auc_flip_tolerant, "auc_flip_tolerant",
                          Read::kOptional));
  // Flipped pairs: pairs.
  t.push_back(Checked(NumberEntry("flipped_pairs.left_right", &S::flipped_left_right,
                                  "flipped_left_right", Read::kRequired),
                      kLower, 0.0));
  t.push_back(Checked(NumberEntry("flipped_pairs.front_back", &S::flipped_front_back,
                                  "flipped_front_back", Read::kRequired),
                      kLower, 0.0));
  t.push_back(Checked(NumberEntry("flipped_pairs.up_down", &S::flipped_up_down,
                                  "flipped_up_down", Read::kRequired),
                      kLower, 0.0));
  {
    Entry e;  // derived from the three above
    e.key = "flipped_pairs.total";
    e.csv_column = "flipped_total";
    e.read = Read::kWritten;
    e.to_json = [](const S& s) { return JsonValue::Number(s.FlippedTotal()); };
    e.csv_cell = [](const S& s) { return std::to_string(s.FlippedTotal()); };
    t.push_back(Checked(e, kLower, 0.0));
  }
  t.push_back(NumberEntry("refine_changed_side.to_symmetric", &S::refine_to_symmetric, "",
                          Read::kOptional, 0.0));
  t.push_back(NumberEntry("refine_changed_side.to_direct", &S::refine_to_direct, "",
                          Read::kOptional, 0.0));
  {
    // Runs only (-1: not known, not written).
    Entry e = NumberEntry("shapes_lost_area", &S::shapes_lost_area, "", Read::kOptional, -1.0);
    e.to_json = [](const S& s) {
      return s.shapes_lost_area >= 0 ? JsonValue::Number(s.shapes_lost_area) : JsonValue();
    };
    t.push_back(e);
  }
  {
    Entry e;
    e.key = "evaluation_geodesics";
    e.read = Read::kRequired;
    e.to_json = [](const S& s) { return JsonValue::String(s.evaluation_geodesics); };
    e.from_json = [](S& s, const JsonValue& v, bool, const std::string& key,
                     const std::string& where) {
      if (!v.IsString()) throw InvalidInputError(where + ": " + key);
      s.evaluation_geodesics = v.AsString();
    };
    t.push_back(e);
  }
  {
    Entry e;  // evaluation.points: a count, or "all" (0)
    e.key = "evaluation_points";
    e.read = Read::kOptional;
    e.to_json = [](const S& s) {
      return s.points_option > 0 ? JsonValue::Number(s.points_option) : JsonValue::String("all");
    };
    e.from_json = [](S& s, const JsonValue& v, bool, const std::string&, const std::string&) {
      s.points_option = static_cast<int>(v.NumberOr(0.0));
    };
    t.push_back(e);
  }
  t.push_back(NumberEntry("max_error", &S::max_error, "", Read::kOptional, S().max_error));
  t.push_back(NumberEntry("step", &S::step, "", Read::kOptional, S().step));
  t.push_back(NumberEntry("time_total_s", &S::time_total_s, "time_total_s", Read::kRequired));
  t.push_back(
      NumberEntry("time_per_shape_s", &S::time_per_shape_s, "time_per_shape_s", Read::kRequired));
  t.push_back(
      NumberEntry("time_per_pair_s", &S::time_per_pair_s, "time_per_pair_s", Read::kRequired));
  t.push_back(NumberEntry("peak_rss_mb", &S::peak_rss_mb, "peak_rss_mb", Read::kRequired));
  return t;
}

// "group.key" -> ("group", "key"); a top-level key -> ("", key). Threshold keys hold a dot
// themselves ("0.05"), so the group ends at the first dot.
std::pair<std::string, std::string> SplitKey(const std::string& key) {
  const size_t dot = key.find('.');
  if (dot == std::string::npos) return {"", key};
  return {key.substr(0, dot), key.substr(dot + 1)};
}

}  // namespace

const std::vector<SummaryEntry>& SummaryEntries() {
  static const std::vector<SummaryEntry> entries = MakeSummaryEntries();
  return entries;
}

JsonValue SummaryToJson(const VariantSummary& s) {
  JsonValue j = JsonValue::Object();
  // Entries of one group are consecutive; the group's object is set when it is complete.
  std::string group;
  JsonValue members = JsonValue::Object();
  const auto flush = [&] {
    if (!group.empty()) j.Set(group, members);
    group.clear();
    members = JsonValue::Object();
  };
  for (const auto& e : SummaryEntries()) {
    const auto [g, key] = SplitKey(e.key);
    if (g != group) flush();
    const JsonValue value = e.to_json(s);
    if (value.IsNull()) continue;
    if (g.empty()) {
      j.Set(key, value);
    } else {
      group = g;
      members.Set(key, value);
    }
  }
  flush();
  return j;
}

VariantSummary SummaryFromJson(const JsonValue& j, const std::string& where) {
  if (!j.IsObject()) throw InvalidInputError(where + ": expected a JSON object");
  VariantSummary s;
  for (const auto& e : SummaryEntries()) {
    if (e.read == SummaryEntry::Read::kWritten) continue;
    const auto [group, key] = SplitKey(e.key);
    const bool required = e.read == SummaryEntry::Read::kRequired;
    const JsonValue* in = &j;
    std::string at = where;
    if (!group.empty()) {
      in = required ? &Require(j, group, where) : &j.Get(group);
      at = where + ": " + group;
    }
    if (required) Require(*in, key, at);
    e.from_json(s, in->Get(key), in->Has(key), key, at);
  }
  return s;
}

void WriteSummaryJson(const std::string& path, const VariantSummary& summary) {
  WriteFileAtomically(path, WriteJson(SummaryToJson(summary)) + "\n");
}

VariantSummary ReadSummaryJson(const std::string& path) {
  return SummaryFromJson(ParseJson(ReadFileOrThrow(path), path), path);
}

const std::vector<PairsCsvColumn>& PairsCsvColumns() {
  using Kind = PairsCsvColumn::Kind;
  using P = const PairEvaluation&;
  // A number the pair has only when it was evaluated.
  const auto if_ok = [](double PairEvaluation::*field) {
    return [field](P p) { return p.ok ? Num(p.*field) : std::string(); };
  };
  const auto message_of = [](const char* stage) {
    return [stage](P p) {
      const auto it = p.stage_messages.find(stage);
      return CsvField(it == p.stage_messages.end() ? std::string() : it->second);
    };
  };
  static const std::vector<PairsCsvColumn> columns = [&] {
    std::vector<PairsCsvColumn> c = {
        {"source", Kind::kText, [](P p) { return CsvField(p.source); }},
        {"target", Kind::kText, [](P p) { return CsvField(p.target); }},
        {"status", Kind::kText, [](P p) { return std::string(p.ok ? "ok" : "failed"); }},
        {"points", Kind::kNumber, [](P p) { return std::to_string(p.ok ? p.points : 0); }},
        {"mean_direct", Kind::kNumber, if_ok(&PairEvaluation::mean_direct)},
        {"median_direct", Kind::kNumber, if_ok(&PairEvaluation::median_direct)},
        {"max_direct", Kind::kNumber, if_ok(&PairEvaluation::max_direct)},
    };
    const auto& keys = ErrorThresholdKeys();
    for (size_t k = 0; k < keys.size(); ++k) {
      c.push_back({"pct_direct_" + keys[k], Kind::kNumber,
                   [k](P p) { return p.ok ? Num(p.pct_direct[k]) : std::string(); }});
    }
    std::vector<PairsCsvColumn> rest = {
        {"mean_sym", Kind::kNumber,
         [](P p) { return p.ok && p.has_sym ? Num(p.mean_sym) : std::string(); }},
        {"mean_flip_tolerant", Kind::kNumber, if_ok(&PairEvaluation::mean_flip_tolerant)},
        {"flip", Kind::kText, [](P p) { return p.ok ? FlipClassName(p.flip) : std::string(); }},
        {"chosen", Kind::kNumber, [](P p) { return std::to_string(p.chosen); }},
        {"oracle", Kind::kNumber, [](P p) { return std::to_string(p.oracle); }},
        {"initial_mean_direct", Kind::kNumber,
         [](P p) { return p.ok && p.refined ? Num(p.initial_mean_direct) : std::string(); }},
        {"refine_side", Kind::kText, [](P p) { return p.RefineSide(); }},
        {"candidate_errors", Kind::kNumberList,
         [](P p) {
           std::string list;
           for (size_t k = 0; k < p.candidate_errors.size(); ++k) {
             list += (k ? " " : "") + Num(p.candidate_errors[k]);
           }
           return list;
         }},
        {"flip_message", Kind::kText, message_of("flip")},
        {"refine_message", Kind::kText, message_of("refine")},
        {"message", Kind::kText, [](P p) { return CsvField(p.message); }},
    };
    c.insert(c.end(), rest.begin(), rest.end());
    return c;
  }();
  return columns;
}

std::string PairsCsv(std::vector<PairEvaluation> pairs) {
  SortPairs(pairs);
  const auto& columns = PairsCsvColumns();
  std::ostringstream out;
  for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c].name;
  out << '\n';
  for (const auto& p : pairs) {
    for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c].cell(p);
    out << '\n';
  }
  return out.str();
}

std::string CurveCsv(const VariantSummary& s) {
  std::ostringstream out;
  out << "threshold,direct,flip_tolerant\n";
  for (size_t k = 0; k < s.thresholds.size(); ++k) {
    out << Num(s.thresholds[k]) << ',' << Num(s.curve_direct[k]) << ','
        << Num(s.curve_flip_tolerant[k]) << '\n';
  }
  return out.str();
}

std::string TimingsCsv(std::vector<PairEvaluation> pairs, const VariantTimings& timings) {
  SortPairs(pairs);
  std::ostringstream out;
  out << "kind,name,stage,seconds\n";
  out << "variant,total,total," << Num(timings.total_seconds) << '\n';
  for (const auto& [shape, stages] : timings.shape_stage_seconds) {
    for (const auto& [stage, seconds] : stages) {
      out << "shape," << CsvField(shape) << ',' << CsvField(stage) << ',' << Num(seconds) << '\n';
    }
  }
  // Each pair under its file stem among these pairs, as the report reads it back beside
  // pairs.csv.
  std::vector<DatasetPair> listed;
  for (const auto& p : pairs) listed.push_back({p.source, p.target});
  const PairNames names(listed);
  for (const auto& p : pairs) {
    const std::string name = CsvField(names.Stem(p.source, p.target));
    for (const auto& [stage, seconds] : p.stage_seconds) {
      out << "pair," << name << ',' << CsvField(stage) << ',' << Num(seconds) << '\n';
    }
  }
  return out.str();
}

std::string ComparisonCsv(const std::vector<VariantSummary>& variants) {
  std::vector<const SummaryEntry*> columns;
  for (const auto& e : SummaryEntries()) {
    if (!e.csv_column.empty()) columns.push_back(&e);
  }
  std::ostringstream out;
  for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c]->csv_column;
  out << '\n';
  for (const auto& s : variants) {
    for (size_t c = 0; c < columns.size(); ++c) out << (c ? "," : "") << columns[c]->csv_cell(s);
    out << '\n';
  }
  return out.str();
}

void WriteVariantOutputs(const std::string& dir, const VariantSummary& summary,
                         const std::vector<PairEvaluation>& pairs, const VariantTimings& timings) {
  WriteSummaryJson(dir + "/summary.json", summary);
  WriteFileAtomically(dir + "/pairs.csv", PairsCsv(pairs));
  WriteFileAtomically(dir + "/curve.csv", CurveCsv(summary));
  WriteFileAtomically(dir + "/timings.csv", TimingsCsv(pairs, timings));
}

bool WriteComparison(const std::string& experiment_dir, const std::vector<VariantSummary>& variants,
                     std::string* warning) {
  WriteFileAtomically(experiment_dir + "/comparison.csv", ComparisonCsv(variants));
  return PlotCurves(experiment_dir, warning);
}

namespace {

// The file of the binary or shared object that holds this code: the symembed binary, or the
// Python module (BUILD/python/symembed/_core*.so) when python3 is the process. Empty if unknown.
fs::path CodeFile() {
  Dl_info info;
  if (dladdr(reinterpret_cast<void*>(&PlotCurves), &info) == 0 || info.dli_fname == nullptr) {
    return {};
  }
  std::error_code ec;
  const fs::path path = fs::canonical(info.dli_fname, ec);
  return ec ? fs::path() : path;
}

std::string FindPlotScript() {
  if (const char* root = std::getenv("SYMEMBED_ROOT")) {
    const fs::path p = fs::path(root) / "scripts" / "plot-curves";
    if (fs::exists(p)) return p.string();
  }
  std::error_code ec;
  for (fs::path dir : {fs::read_symlink("/proc/self/exe", ec).parent_path(),
                       CodeFile().parent_path()}) {
    for (int up = 0; up < 5 && !dir.empty(); ++up) {
      const fs::path p = dir / "scripts" / "plot-curves";
      if (fs::exists(p)) return p.string();
      if (dir == dir.parent_path()) break;
      dir = dir.parent_path();
    }
  }
  return "";
}

// Runs argv[0] with argv (stdout and stderr to /dev/null) and returns its wait status, or -1 when
// it could not be started. The child dies with this process: a run killed while it plots must
// not leave a helper that writes figures later.
int RunChild(const std::vector<std::string>& argv) {
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(126);  // the parent died before prctl took effect
    const int null_fd = open("/dev/null", O_WRONLY);
    if (null_fd >= 0) {
      dup2(null_fd, 1);
      dup2(null_fd, 2);
    }
    std::vector<char*> args;
    for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return status;
}

}  // namespace

bool PlotCurves(const std::string& dir, std::string* warning) {
  auto fail = [&](const std::string& why) {
    if (warning) *warning = "no curve plot: " + why;
    return false;
  };
  const std::string python = "/usr/bin/python3";
  if (access(python.c_str(), X_OK) != 0) return fail(python + " not found");
  const std::string script = FindPlotScript();
  if (script.empty()) return fail("scripts/plot-curves not found (set SYMEMBED_ROOT)");
  const int status = RunChild({python, script, dir});
  if (status < 0) return fail("cannot start " + python);
  if (status != 0) {
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return fail(code == 3 ? "matplotlib is not installed for " + python
                          : "plot-curves failed (exit " + std::to_string(code) + ")");
  }
  return true;
}

namespace {

// One member of the pair record (pairs/STEM.rec), in the record's order: its value (none: the
// pair has none, the member is left out) and how it is read back. Members are read in this
// order, so a member may depend on one above it (the errors and the flip class are read only for
// a pair that was scored, `ok`). Adding a member to the record is one row.
struct RecordMember {
  const char* key;
  std::function<std::optional<JsonValue>(const PairEvaluation&)> write;
  std::function<void(const JsonValue& record, const std::string& where, PairEvaluation*)> read;
};

const std::vector<RecordMember>& RecordMembers() {
  using P = PairEvaluation;
  using J = JsonValue;
  using V = std::optional<JsonValue>;
  using W = const std::string&;
  static const std::vector<RecordMember> members = {
      {"source", [](const P& p) -> V { return J::String(p.source); },
       [](const J& j, W where, P* p) { p->source = Require(j, "source", where).AsString(); }},
      {"target", [](const P& p) -> V { return J::String(p.target); },
       [](const J& j, W where, P* p) { p->target = Require(j, "target", where).AsString(); }},
      {"ok", [](const P& p) -> V { return J::Bool(p.ok); },
       [](const J& j, W where, P* p) { p->ok = Require(j, "ok", where).AsBool(); }},
      {"message", [](const P& p) -> V { return J::String(p.message); },
       [](const J& j, W where, P* p) { p->message = Require(j, "message", where).AsString(); }},
      // Read with the errors, after the statistics (errors_sym's row).
      {"flip", [](const P& p) -> V { return J::String(FlipClassName(p.flip)); }, nullptr},
      {"chosen", [](const P& p) -> V { return J::Number(p.chosen); },
       [](const J& j, W where, P* p) {
         p->chosen = static_cast<int>(RequireNumber(j, "chosen", where));
       }},
      {"oracle", [](const P& p) -> V { return J::Number(p.oracle); },
       [](const J& j, W where, P* p) {
         p->oracle = static_cast<int>(RequireNumber(j, "oracle", where));
       }},
      {"stage_seconds",
       [](const P& p) -> V {
         J stages = J::Object();
         for (const auto& [stage, seconds] : p.stage_seconds) stages.Set(stage, J::Number(seconds));
         return stages;
       },
       [](const J& j, W where, P* p) {
         for (const auto& [stage, seconds] : Require(j, "stage_seconds", where).members()) {
           p->stage_seconds[stage] = seconds.NumberOr(kNaN);
         }
       }},
      // Optional (records written before it existed have none).
      {"stage_messages",
       [](const P& p) -> V {
         if (p.stage_messages.empty()) return std::nullopt;
         J messages = J::Object();
         for (const auto& [stage, message] : p.stage_messages) {
           messages.Set(stage, J::String(message));
         }
         return messages;
       },
       [](const J& j, W, P* p) {
         if (!j.Get("stage_messages").IsObject()) return;
         for (const auto& [stage, message] : j.Get("stage_messages").members()) {
           p->stage_messages[stage] = message.AsString();
         }
       }},
      // Optional, as stage_messages.
      {"candidate_errors",
       [](const P& p) -> V {
         if (p.candidate_errors.empty()) return std::nullopt;
         return NumberArray(p.candidate_errors);
       },
       [](const J& j, W where, P* p) {
         if (j.Get("candidate_errors").IsArray()) {
           p->candidate_errors = ReadNumberArray(j.Get("candidate_errors"), where);
         }
       }},
      // The errors, then what follows from them, then the flip class: a scored pair only.
      {"errors_direct", [](const P& p) -> V { return NumberArray(p.errors_direct); },
       [](const J& j, W where, P* p) {
         if (!p->ok) return;
         p->errors_direct = ReadNumberArray(Require(j, "errors_direct", where), where);
       }},
      {"errors_sym", [](const P& p) -> V { return NumberArray(p.errors_sym); },
       [](const J& j, W where, P* p) {
         if (!p->ok) return;
         p->errors_sym = ReadNumberArray(Require(j, "errors_sym", where), where);
         if (!p->errors_sym.empty() && p->errors_sym.size() != p->errors_direct.size()) {
           throw InvalidInputError(where + ": errors_sym and errors_direct differ in length");
         }
         ComputePairStatistics(*p);
         p->flip = ParseFlipClass(Require(j, "flip", where).AsString());
       }},
      // A refined pair's errors before refinement: both members, or neither.
      {"initial_mean_direct",
       [](const P& p) -> V {
         if (!p.refined) return std::nullopt;
         return J::Number(p.initial_mean_direct);
       },
       [](const J& j, W where, P* p) {
         if (!p->ok || !j.Get("initial_mean_direct").IsNumber()) return;
         p->refined = true;
         p->initial_mean_direct = RequireNumber(j, "initial_mean_direct", where);
       }},
      {"initial_mean_sym",
       [](const P& p) -> V {
         if (!p.refined) return std::nullopt;
         return J::Number(p.initial_mean_sym);
       },
       [](const J& j, W where, P* p) {
         if (p->refined) p->initial_mean_sym = RequireNumber(j, "initial_mean_sym", where);
       }},
  };
  return members;
}

}  // namespace

std::string SerializePairRecord(const PairEvaluation& p) {
  JsonValue j = JsonValue::Object();
  for (const RecordMember& m : RecordMembers()) {
    if (std::optional<JsonValue> value = m.write(p)) j.Set(m.key, std::move(*value));
  }
  const std::string members = WriteJson(j, 0);
  if (!p.inputs) return members;
  return "{\"inputs\":{\"source\":\"" + HexDigest(p.inputs->source) + "\",\"target\":\"" +
         HexDigest(p.inputs->target) + "\",\"pair\":\"" + HexDigest(p.inputs->pair) + "\"}," +
         members.substr(1);
}

namespace {

// The `inputs` member of a record: {"source", "target", "pair"}, each 16 lowercase hex digits.
PairInputs ReadPairInputs(const JsonValue& json, const std::string& where) {
  const auto hex = [&](const char* key) {
    const JsonValue& value = json.Get(key);
    const std::optional<uint64_t> digest =
        value.IsString() ? ParseHexDigest(value.AsString()) : std::nullopt;
    if (!digest) {
      throw InvalidInputError(where + ": inputs: expected source, target and pair of 16 hex "
                                      "digits each");
    }
    return *digest;
  };
  if (!json.IsObject()) throw InvalidInputError(where + ": inputs: expected an object");
  PairInputs inputs;
  inputs.source = hex("source");
  inputs.target = hex("target");
  inputs.pair = hex("pair");
  return inputs;
}

}  // namespace

PairEvaluation ParsePairRecord(const std::string& text, const std::string& where) {
  const JsonValue j = ParseJson(text, where);
  if (!j.IsObject()) throw InvalidInputError(where + ": expected a JSON object");
  PairEvaluation p;
  if (j.Has("inputs")) p.inputs = ReadPairInputs(j.Get("inputs"), where);
  for (const RecordMember& m : RecordMembers()) {
    if (m.read) m.read(j, where, &p);
  }
  return p;
}

}  // namespace symembed

#include "eval/report.h"

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
#include <sstream>

#include "core/errors.h"
#include "registry/files.h"
#include "registry/pair_names.h"

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

std::string CsvField(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += c;
  }
  return out + "\"";
}

JsonValue Thresholded(const std::array<double, 3>& values) {
  JsonValue o = JsonValue::Object();
  for (size_t k = 0; k < values.size(); ++k) {
    o.Set(ErrorThresholdKeys()[k], JsonValue::Number(values[k]));
  }
  return o;
}

const JsonValue& Require(const JsonValue& json, const std::string& key, const std::string& where) {
  if (!json.Has(key)) throw InvalidInputError(where + ": missing key '" + key + "'");
  return json.Get(key);
}

double RequireNumber(const JsonValue& json, const std::string& key, const std::string& where) {
  const JsonValue& v = Require(json, key, where);
  if (!v.IsNumber() && !v.IsNull()) {
    throw InvalidInputError(where + ": key '" + key + "' must be a number");
  }
  return v.NumberOr(kNaN);
}

std::array<double, 3> RequireThresholded(const JsonValue& json, const std::string& key,
                                         const std::string& where) {
  const JsonValue& o = Require(json, key, where);
  std::array<double, 3> values{};
  for (size_t k = 0; k < values.size(); ++k) {
    values[k] = RequireNumber(o, ErrorThresholdKeys()[k], where + ": " + key);
  }
  return values;
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

JsonValue SummaryToJson(const VariantSummary& s) {
  JsonValue j = JsonValue::Object();
  j.Set("variant", JsonValue::String(s.variant));
  j.Set("pairs", JsonValue::Number(s.pairs));
  j.Set("failed_pairs", JsonValue::Number(s.failed_pairs));
  j.Set("points", JsonValue::Number(static_cast<double>(s.total_points)));
  j.Set("mean_direct", JsonValue::Number(s.mean_direct));
  j.Set("median_direct", JsonValue::Number(s.median_direct));
  j.Set("mean_flip_tolerant", JsonValue::Number(s.mean_flip_tolerant));
  j.Set("median_flip_tolerant", JsonValue::Number(s.median_flip_tolerant));
  j.Set("mean_of_pair_means_direct", JsonValue::Number(s.mean_of_pair_means_direct));
  j.Set("mean_of_pair_means_flip_tolerant", JsonValue::Number(s.mean_of_pair_means_flip_tolerant));
  j.Set("pct_direct", Thresholded(s.pct_direct));
  j.Set("pct_flip_tolerant", Thresholded(s.pct_flip_tolerant));
  j.Set("auc_direct", JsonValue::Number(s.auc_direct));
  j.Set("auc_flip_tolerant", JsonValue::Number(s.auc_flip_tolerant));
  JsonValue flips = JsonValue::Object();
  flips.Set("left_right", JsonValue::Number(s.flipped_left_right));
  flips.Set("front_back", JsonValue::Number(s.flipped_front_back));
  flips.Set("up_down", JsonValue::Number(s.flipped_up_down));
  flips.Set("total", JsonValue::Number(s.FlippedTotal()));
  j.Set("flipped_pairs", flips);
  JsonValue refine = JsonValue::Object();
  refine.Set("to_symmetric", JsonValue::Number(s.refine_to_symmetric));
  refine.Set("to_direct", JsonValue::Number(s.refine_to_direct));
  j.Set("refine_changed_side", refine);
  if (s.shapes_lost_area >= 0) j.Set("shapes_lost_area", JsonValue::Number(s.shapes_lost_area));
  j.Set("evaluation_geodesics", JsonValue::String(s.evaluation_geodesics));
  j.Set("evaluation_points",
        s.points_option > 0 ? JsonValue::Number(s.points_option) : JsonValue::String("all"));
  j.Set("max_error", JsonValue::Number(s.max_error));
  j.Set("step", JsonValue::Number(s.step));
  j.Set("time_total_s", JsonValue::Number(s.time_total_s));
  j.Set("time_per_shape_s", JsonValue::Number(s.time_per_shape_s));
  j.Set("time_per_pair_s", JsonValue::Number(s.time_per_pair_s));
  j.Set("peak_rss_mb", JsonValue::Number(s.peak_rss_mb));
  return j;
}

VariantSummary SummaryFromJson(const JsonValue& j, const std::string& where) {
  if (!j.IsObject()) throw InvalidInputError(where + ": expected a JSON object");
  VariantSummary s;
  if (j.Get("variant").IsString()) s.variant = j.Get("variant").AsString();
  s.pairs = static_cast<int>(RequireNumber(j, "pairs", where));
  s.failed_pairs = static_cast<int>(RequireNumber(j, "failed_pairs", where));
  s.total_points = static_cast<long>(j.Get("points").NumberOr(0.0));
  s.mean_direct = RequireNumber(j, "mean_direct", where);
  s.median_direct = RequireNumber(j, "median_direct", where);
  s.mean_flip_tolerant = RequireNumber(j, "mean_flip_tolerant", where);
  s.median_flip_tolerant = j.Get("median_flip_tolerant").NumberOr(kNaN);
  s.mean_of_pair_means_direct = j.Get("mean_of_pair_means_direct").NumberOr(kNaN);
  s.mean_of_pair_means_flip_tolerant = j.Get("mean_of_pair_means_flip_tolerant").NumberOr(kNaN);
  s.pct_direct = RequireThresholded(j, "pct_direct", where);
  s.pct_flip_tolerant = RequireThresholded(j, "pct_flip_tolerant", where);
  s.auc_direct = RequireNumber(j, "auc_direct", where);
  s.auc_flip_tolerant = j.Get("auc_flip_tolerant").NumberOr(kNaN);
  const JsonValue& flips = Require(j, "flipped_pairs", where);
  s.flipped_left_right = static_cast<int>(RequireNumber(flips, "left_right", where));
  s.flipped_front_back = static_cast<int>(RequireNumber(flips, "front_back", where));
  s.flipped_up_down = static_cast<int>(RequireNumber(flips, "up_down", where));
  const JsonValue& refine = j.Get("refine_changed_side");
  s.refine_to_symmetric = static_cast<int>(refine.Get("to_symmetric").NumberOr(0.0));
  s.refine_to_direct = static_cast<int>(refine.Get("to_direct").NumberOr(0.0));
  s.shapes_lost_area = static_cast<int>(j.Get("shapes_lost_area").NumberOr(-1.0));
  const JsonValue& geodesics = Require(j, "evaluation_geodesics", where);
  if (!geodesics.IsString()) throw InvalidInputError(where + ": evaluation_geodesics");
  s.evaluation_geodesics = geodesics.AsString();
  s.points_option = static_cast<int>(j.Get("evaluation_points").NumberOr(0.0));
  s.max_error = j.Get("max_error").NumberOr(s.max_error);
  s.step = j.Get("step").NumberOr(s.step);
  s.time_total_s = RequireNumber(j, "time_total_s", where);
  s.time_per_shape_s = RequireNumber(j, "time_per_shape_s", where);
  s.time_per_pair_s = RequireNumber(j, "time_per_pair_s", where);
  s.peak_rss_mb = RequireNumber(j, "peak_rss_mb", where);
  return s;
}

void WriteSummaryJson(const std::string& path, const VariantSummary& summary) {
  WriteFileAtomically(path, WriteJson(SummaryToJson(summary)) + "\n");
}

VariantSummary ReadSummaryJson(const std::string& path) {
  return SummaryFromJson(ParseJson(ReadFileOrThrow(path), path), path);
}

std::string PairsCsv(std::vector<PairEvaluation> pairs) {
  SortPairs(pairs);
  std::ostringstream out;
  out << "source,target,status,points,mean_direct,median_direct,max_direct";
  for (const auto& key : ErrorThresholdKeys()) out << ",pct_direct_" << key;
  out << ",mean_sym,mean_flip_tolerant,flip,chosen,oracle,initial_mean_direct,refine_side,"
         "candidate_errors,flip_message,refine_message,message\n";
  for (const auto& p : pairs) {
    out << CsvField(p.source) << ',' << CsvField(p.target) << ',' << (p.ok ? "ok" : "failed");
    if (p.ok) {
      out << ',' << p.points << ',' << Num(p.mean_direct) << ',' << Num(p.median_direct) << ','
          << Num(p.max_direct);
      for (double pct : p.pct_direct) out << ',' << Num(pct);
      out << ',' << (p.has_sym ? Num(p.mean_sym) : "") << ',' << Num(p.mean_flip_tolerant) << ','
          << FlipClassName(p.flip);
    } else {
      out << ",0,,,,,,,,,";
    }
    out << ',' << p.chosen << ',' << p.oracle << ','
        << (p.ok && p.refined ? Num(p.initial_mean_direct) : "") << ',' << p.RefineSide() << ',';
    for (size_t k = 0; k < p.candidate_errors.size(); ++k) {
      out << (k ? " " : "") << Num(p.candidate_errors[k]);
    }
    const auto message_of = [&](const char* stage) {
      const auto it = p.stage_messages.find(stage);
      return it == p.stage_messages.end() ? std::string() : it->second;
    };
    out << ',' << CsvField(message_of("flip")) << ',' << CsvField(message_of("refine")) << ','
        << CsvField(p.message) << '\n';
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
  std::ostringstream out;
  out << "variant,pairs,failed_pairs,mean_direct,median_direct,mean_flip_tolerant";
  for (const auto& key : ErrorThresholdKeys()) out << ",pct_direct_" << key;
  for (const auto& key : ErrorThresholdKeys()) out << ",pct_flip_tolerant_" << key;
  out << ",auc_direct,auc_flip_tolerant,flipped_left_right,flipped_front_back,flipped_up_down,"
         "flipped_total,time_total_s,time_per_shape_s,time_per_pair_s,peak_rss_mb\n";
  for (const auto& s : variants) {
    out << CsvField(s.variant) << ',' << s.pairs << ',' << s.failed_pairs << ','
        << Num(s.mean_direct) << ',' << Num(s.median_direct) << ',' << Num(s.mean_flip_tolerant);
    for (double pct : s.pct_direct) out << ',' << Num(pct);
    for (double pct : s.pct_flip_tolerant) out << ',' << Num(pct);
    out << ',' << Num(s.auc_direct) << ',' << Num(s.auc_flip_tolerant) << ','
        << s.flipped_left_right << ',' << s.flipped_front_back << ',' << s.flipped_up_down << ','
        << s.FlippedTotal() << ',' << Num(s.time_total_s) << ',' << Num(s.time_per_shape_s) << ','
        << Num(s.time_per_pair_s) << ',' << Num(s.peak_rss_mb) << '\n';
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

std::string FindPlotScript() {
  if (const char* root = std::getenv("SYMEMBED_ROOT")) {
    const fs::path p = fs::path(root) / "scripts" / "plot-curves";
    if (fs::exists(p)) return p.string();
  }
  std::error_code ec;
  fs::path dir = fs::read_symlink("/proc/self/exe", ec).parent_path();
  for (int up = 0; !ec && up < 5 && !dir.empty(); ++up) {
    const fs::path p = dir / "scripts" / "plot-curves";
    if (fs::exists(p)) return p.string();
    if (dir == dir.parent_path()) break;
    dir = dir.parent_path();
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

std::string SerializePairRecord(const PairEvaluation& p) {
  JsonValue j = JsonValue::Object();
  j.Set("source", JsonValue::String(p.source));
  j.Set("target", JsonValue::String(p.target));
  j.Set("ok", JsonValue::Bool(p.ok));
  j.Set("message", JsonValue::String(p.message));
  j.Set("flip", JsonValue::String(FlipClassName(p.flip)));
  j.Set("chosen", JsonValue::Number(p.chosen));
  j.Set("oracle", JsonValue::Number(p.oracle));
  JsonValue stages = JsonValue::Object();
  for (const auto& [stage, seconds] : p.stage_seconds) {
    stages.Set(stage, JsonValue::Number(seconds));
  }
  j.Set("stage_seconds", stages);
  if (!p.stage_messages.empty()) {
    JsonValue messages = JsonValue::Object();
    for (const auto& [stage, message] : p.stage_messages) {
      messages.Set(stage, JsonValue::String(message));
    }
    j.Set("stage_messages", messages);
  }
  if (!p.candidate_errors.empty()) j.Set("candidate_errors", NumberArray(p.candidate_errors));
  j.Set("errors_direct", NumberArray(p.errors_direct));
  j.Set("errors_sym", NumberArray(p.errors_sym));
  if (p.refined) {
    j.Set("initial_mean_direct", JsonValue::Number(p.initial_mean_direct));
    j.Set("initial_mean_sym", JsonValue::Number(p.initial_mean_sym));
  }
  return WriteJson(j, 0);
}

PairEvaluation ParsePairRecord(const std::string& text, const std::string& where) {
  const JsonValue j = ParseJson(text, where);
  if (!j.IsObject()) throw InvalidInputError(where + ": expected a JSON object");
  PairEvaluation p;
  p.source = Require(j, "source", where).AsString();
  p.target = Require(j, "target", where).AsString();
  p.ok = Require(j, "ok", where).AsBool();
  p.message = Require(j, "message", where).AsString();
  p.chosen = static_cast<int>(RequireNumber(j, "chosen", where));
  p.oracle = static_cast<int>(RequireNumber(j, "oracle", where));
  for (const auto& [stage, seconds] : Require(j, "stage_seconds", where).members()) {
    p.stage_seconds[stage] = seconds.NumberOr(kNaN);
  }
  // Optional (records written before they existed have neither).
  if (j.Get("stage_messages").IsObject()) {
    for (const auto& [stage, message] : j.Get("stage_messages").members()) {
      p.stage_messages[stage] = message.AsString();
    }
  }
  if (j.Get("candidate_errors").IsArray()) {
    p.candidate_errors = ReadNumberArray(j.Get("candidate_errors"), where);
  }
  if (p.ok) {
    p.errors_direct = ReadNumberArray(Require(j, "errors_direct", where), where);
    p.errors_sym = ReadNumberArray(Require(j, "errors_sym", where), where);
    if (!p.errors_sym.empty() && p.errors_sym.size() != p.errors_direct.size()) {
      throw InvalidInputError(where + ": errors_sym and errors_direct differ in length");
    }
    ComputePairStatistics(p);
    p.flip = ParseFlipClass(Require(j, "flip", where).AsString());
    if (j.Get("initial_mean_direct").IsNumber()) {
      p.refined = true;
      p.initial_mean_direct = RequireNumber(j, "initial_mean_direct", where);
      p.initial_mean_sym = RequireNumber(j, "initial_mean_sym", where);
    }
  }
  return p;
}

}  // namespace symembed

// symembed eval --dataset CONFIG_OR_DIR --maps DIR --base 0|1 --name NAME [...]
#include <filesystem>
#include <iostream>

#include "apps/args.h"
#include "apps/commands.h"
#include "core/errors.h"
#include "eval/evaluator.h"
#include "eval/report.h"
#include "eval/score_maps.h"
#include "harness/config.h"
#include "harness/eval_setup.h"
#include "harness/run_outputs.h"

namespace symembed {

namespace {

int ParsePoints(const std::string& text) {
  if (text == "all") return 0;
  try {
    size_t used = 0;
    const int n = std::stoi(text, &used);
    if (used == text.size() && n > 0) return n;
  } catch (const std::exception&) {
  }
  throw UsageError{"--points expects 'all' or a positive integer, got '" + text + "'"};
}

// The eval's setup from --dataset (MakeEvalSetup), with --geodesics and --points applied.
EvalSetup ReadEvalSetup(const ArgParser& parser, const Registry& registry) {
  EvalSetup s = MakeEvalSetup(parser.Get("dataset"), registry);
  if (parser.Given("geodesics") || !s.geodesics) {
    if (parser.Given("geodesics")) s.evaluation.geodesics = parser.Get("geodesics");
    YAML::Node node;
    node["type"] = s.evaluation.geodesics;
    s.geodesics =
        registry.CreateAs<GeodesicsStage>("geodesics", node, "--geodesics", "evaluation.geodesics");
  }
  if (parser.Given("points")) s.evaluation.points = ParsePoints(parser.Get("points"));
  return s;
}

// The failed pairs on stderr, the summary line on stdout.
void PrintEvalReport(const std::string& name, const std::string& out, const ScoreMapsResult& result,
                     const VariantSummary& summary) {
  for (const auto& p : result.pairs) {
    if (!p.ok)
      std::cerr << "symembed eval: " << p.source << " -> " << p.target << ": " << p.message << "\n";
  }
  for (const std::string& warning : result.warnings) {
    std::cerr << "symembed eval: warning: " << warning << "\n";
  }
  std::cout << "eval " << name << ": " << summary.pairs << " pairs, " << summary.failed_pairs
            << " failed; mean error direct " << summary.mean_direct << ", flip-tolerant "
            << summary.mean_flip_tolerant << "; flipped pairs " << summary.FlippedTotal()
            << " (left-right " << summary.flipped_left_right << "); outputs in " << out << "\n";
}

// The command's options.
ArgParser EvalParser() {
  ArgParser parser(
      "eval",
      "Score a folder of map files A_B.map (one target vertex id per source vertex, in the ids "
      "of the input meshes) for the pairs of a dataset, with the evaluator of `symembed run`: "
      "geodesic errors d_B(T(a_i), b_i) / sqrt(area(B)) on the preprocessed target, curves, "
      "flip-tolerant errors and left-right flips. Writes summary.json, pairs.csv, curve.csv, "
      "timings.csv (and curves.png/svg when matplotlib is available), eval.json (the inputs) and "
      "the HTML report report/index.html into the output folder. "
      "Where two pairs would share a name A_B.map (p_q1 -> r1 and p -> q1_r1) or a name holds "
      "'%', those pairs' files have the source escaped ('%' as %25, '_' as %5F: p%5Fq1_r1.map), "
      "as `symembed run` names them. "
      "A missing or malformed map (wrong length, NaN, non-integral or out-of-range ids) fails "
      "only its pair, with the file and line in pairs.csv and on stderr. Exit code 0 when "
      "every pair was scored, 1 when some failed.");
  parser.Option("dataset",
                "an experiment config (its dataset, preprocess and evaluation are used) or a "
                "dataset folder in the pairs_vts layout (default preprocess)",
                "");
  parser.Option("maps", "folder with the A_B.map files", "");
  parser.Option("base", "0 or 1: the id of the first vertex in the map files", "");
  parser.Option("name", "name of the evaluation (output folder results/NAME)", "--out's folder name");
  parser.Option("geodesics",
                "geodesics stage of the evaluation (dijkstra, fast_marching, "
                "heat; default: the config's, else fast_marching)",
                "");
  parser.Option("points", "ground-truth points per pair: all, or N farthest-point samples",
                "config's, else all");
  parser.Switch("reverse", "the file A_B.map maps B to A (scored as the pair B -> A)");
  parser.Option("out", "output folder", "results/NAME");
  parser.Option("jobs", "worker threads (0 = all cores)", "0");
  parser.Option("cache-mb", "memory budget of the geodesic distance cache in MiB",
                std::to_string(static_cast<int>(kDefaultEvaluationCacheMb)));
  parser.Switch("no-report", "do not write the HTML report (OUT/report; see symembed report)");
  return parser;
}

// The map-scoring options of the arguments. Throws UsageError, IoError for a missing maps
// folder; refuses the maps of a run that has not finished.
ScoreMapsOptions ScoreMapsOptionsOf(const ArgParser& parser) {
  for (const char* required : {"dataset", "maps", "base"}) {
    if (!parser.Given(required)) throw UsageError{std::string("--") + required + " is required"};
  }
  if (!parser.Given("name") && !parser.Given("out")) {
    throw UsageError{"--name (or --out) is required"};
  }
  ScoreMapsOptions options;
  options.maps_dir = parser.Get("maps");
  options.base = parser.GetInt("base");
  options.reverse = parser.Flag("reverse");
  options.threads = parser.GetInt("jobs");
  std::string error;
  if (!options.IsValid(&error)) throw UsageError{error};
  // The maps of a run that has not finished are not all there (the folder may not exist yet):
  // that is said first.
  std::filesystem::path maps_path = std::filesystem::path(options.maps_dir).lexically_normal();
  if (maps_path.filename().empty()) maps_path = maps_path.parent_path();
  if (maps_path.has_parent_path()) RequireNotInProgress(maps_path.parent_path().string());
  if (!std::filesystem::is_directory(options.maps_dir)) {
    throw IoError(options.maps_dir + ": maps folder not found");
  }
  return options;
}

}  // namespace

int EvalCommand(const Args& args) {
  ArgParser parser = EvalParser();
  if (!parser.Parse(args)) return 0;
  const ScoreMapsOptions options = ScoreMapsOptionsOf(parser);
  const std::string out = parser.Given("out") ? parser.Get("out") : "results/" + parser.Get("name");
  std::filesystem::path out_path = std::filesystem::path(out).lexically_normal();
  if (out_path.filename().empty()) out_path = out_path.parent_path();
  const std::string name = parser.Given("name") ? parser.Get("name") : out_path.filename().string();

  Registry registry;
  RegisterBuiltinStages(registry);
  EvalSetup setup = ReadEvalSetup(parser, registry);
  const EvaluationOptions& evaluation = setup.evaluation;

  double cache_mb = 2048;
  try {
    cache_mb = std::stod(parser.Get("cache-mb"));
  } catch (const std::exception&) {
    throw UsageError{"--cache-mb expects a number"};
  }
  const Evaluator evaluator(evaluation, *setup.geodesics, cache_mb);
  const ScoreMapsResult result = ScoreMaps(*setup.dataset, *setup.preprocess, evaluator, options);
  const VariantSummary summary = Summarize(name, result.pairs, evaluation, result.timings);
  MarkInProgress(out, "symembed eval");
  WriteVariantOutputs(out, summary, result.pairs, result.timings);
  WriteEvalSource(
      out, EvalSource{parser.Get("dataset"), options.maps_dir, options.base, options.reverse});
  ClearInProgress(out);
  std::string warning;
  if (!PlotCurves(out, &warning)) std::cerr << "symembed eval: warning: " << warning << "\n";

  PrintEvalReport(name, out, result, summary);
  if (!parser.Flag("no-report")) ReportAfterCommand("eval", out, registry);
  return summary.failed_pairs > 0 ? 1 : 0;
}

}  // namespace symembed

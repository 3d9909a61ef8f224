// Evaluator speed on a TOSCA pair (cat0 -> cat1, about 5,000 vertices, 5,000 ground-truth
// lines), for every registered geodesics stage.
//
// BM_EvaluateCold/<geodesics>: a fresh Evaluator per iteration, so the distances from every
// ground-truth point of the target are computed (the cost of the first pair of a target).
// BM_EvaluateWarm/<geodesics>: the same pair again with the target's distances cached (the
// cost of every later pair with that target). BM_EvaluatePoints1024: cold, evaluation.points
// = 1024 with fast marching. Skipped without the TOSCA data (set SYMEMBED_DATA).
#include <benchmark/benchmark.h>

#include <fstream>

#include "core/mesh_io.h"
#include "eval/evaluator.h"
#include "harness/config.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

struct ToscaPair {
  bool ok = false;
  EvalShape target;
  std::vector<int> map;  // the ground-truth map on ground-truth lines, 0 elsewhere
  InputGroundTruth gt;
};

ShapeGroundTruth ReadVts(const std::string& base) {
  ShapeGroundTruth gt;
  for (const auto& [suffix, ids] : {std::make_pair(".vts", &gt.ids),
                                    std::make_pair(".sym.vts", &gt.sym_ids)}) {
    std::ifstream in(base + suffix);
    for (int id; in >> id;) ids->push_back(id - 1);
  }
  return gt;
}

const ToscaPair& Pair() {
  static const ToscaPair pair = [] {
    ToscaPair p;
    const std::string root = testing::DataRoot();
    if (root.empty()) return p;
    const std::string dir = root + "/tosca_iso_5k/";
    const Surface a = LoadSurface(dir + "shapes/cat0.off");
    const Surface b = LoadSurface(dir + "shapes/cat1.off");
    Registry registry;
    RegisterBuiltinStages(registry);
    auto preprocess = registry.CreateAs<PreprocessStage>("preprocess", YAML::Node(), "bench",
                                                         "preprocess", "standard");
    p.target = MakeEvalShape(preprocess->Run(b), b);
    p.gt = PairLines(ReadVts(dir + "corres/cat0"), ReadVts(dir + "corres/cat1"));
    p.map.assign(a.NumVertices(), 0);
    for (size_t i = 0; i < p.gt.source_ids.size(); ++i) p.map[p.gt.source_ids[i]] = p.gt.target_ids[i];
    p.ok = true;
    return p;
  }();
  return pair;
}

std::unique_ptr<GeodesicsStage> Geodesics(const std::string& type) {
  Registry registry;
  RegisterBuiltinStages(registry);
  YAML::Node node;
  node["type"] = type;
  return registry.CreateAs<GeodesicsStage>("geodesics", node, "bench", "evaluation.geodesics");
}

void BM_Evaluate(benchmark::State& state, const std::string& type, bool warm, int points) {
  const ToscaPair& pair = Pair();
  if (!pair.ok) {
    state.SkipWithError("TOSCA data not found (set SYMEMBED_DATA)");
    return;
  }
  const auto geodesics = Geodesics(type);
  EvaluationOptions options;
  options.geodesics = type;
  options.points = points;
  Evaluator shared(options, *geodesics);
  if (warm) shared.Evaluate("cat0", "cat1", pair.target, pair.map, pair.gt);
  double mean = 0.0, sym = 0.0;
  for (auto _ : state) {
    Evaluator fresh(options, *geodesics);
    const Evaluator& evaluator = warm ? shared : fresh;
    const PairEvaluation e = evaluator.Evaluate("cat0", "cat1", pair.target, pair.map, pair.gt);
    mean = e.mean_direct;
    sym = e.mean_sym;
    benchmark::DoNotOptimize(mean);
  }
  state.SetLabel("lines=" + std::to_string(pair.gt.target_ids.size()) +
                 " mean_error=" + std::to_string(mean) + " mean_sym=" + std::to_string(sym));
}

void RegisterAll() {
  Registry registry;
  RegisterBuiltinStages(registry);
  for (const auto& type : registry.Names("geodesics")) {
    benchmark::RegisterBenchmark(("BM_EvaluateCold/" + type).c_str(), BM_Evaluate, type, false, 0)
        ->Unit(benchmark::kMillisecond)->Iterations(1);
    benchmark::RegisterBenchmark(("BM_EvaluateWarm/" + type).c_str(), BM_Evaluate, type, true, 0)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("BM_EvaluatePoints1024/fast_marching", BM_Evaluate,
                               std::string("fast_marching"), false, 1024)
      ->Unit(benchmark::kMillisecond)->Iterations(1);
}

}  // namespace
}  // namespace symembed

int main(int argc, char** argv) {
  symembed::RegisterAll();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

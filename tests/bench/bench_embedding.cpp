// Embedding speed on a synthetic figure with graph geodesics (registered `dijkstra`), built
// outside the timed loops.
//
// BM_Embedding/<type>/<samples>: the registered stage end to end (sample embedding and every
//   other vertex), on the humanoid rest pose with about 5,000 vertices.
// BM_Smacof/<samples>: SMACOF alone from the `original` init (the 1,000-sample target: < 0.5 s).
// BM_ClassicalMds/<samples>: classical MDS alone (the 1,000-sample target: < 0.3 s).
// BM_OutOfSample/<vertices>: placement of every vertex from 1,000 samples (target for 5,000
//   vertices: < 0.1 s); the 50,000-vertex figure is a denser rest pose.
// BM_SmacofTosca/<shape>: SMACOF on 1,000 FPS samples of TOSCA shapes (skipped without data).
// Time is wall-clock; CPU is the process's CPU time over all threads (stages run on
// DefaultThreadCount() threads; SYMEMBED_THREADS overrides).
// Counters: iterations (accepted updates), evaluations (O(n^2) stress passes), stress
// (normalised).
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "core/mds/classical_mds.h"
#include "core/mds/smacof.h"
#include "core/mesh_io.h"
#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"
#include "stages/embedding/embedding_common.h"
#include "stages/embedding/lsmds.h"
#include "stages/embedding/out_of_sample.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

const Registry& Builtins() {
  static const Registry registry = [] {
    Registry r;
    RegisterBuiltinStages(r);
    return r;
  }();
  return registry;
}

Surface Figure(int vertices) {
  SynthOptions options;
  options.poses = 1;
  options.vertices = vertices;
  return GenerateClass(FigureKind::kHumanoid, options).shapes[0].shape.surface;
}

struct Input {
  Surface surface;
  std::vector<int> samples;
  Eigen::MatrixXd D;     // #S x #V
  Eigen::MatrixXd Dss;   // #S x #S
  Eigen::MatrixXd init;  // `original` init of the samples
};

std::unique_ptr<Input> MakeInput(Surface surface, int samples) {
  auto in = std::make_unique<Input>();
  in->surface = std::move(surface);
  const Registry& r = Builtins();
  in->samples =
      r.CreateAs<SamplingStage>(
           "sampling", YAML::Load("{type: farthest_point, count: " + std::to_string(samples) + "}"),
           "bench", "sampling")
          ->Run(in->surface)
          .samples;
  in->D =
      r.CreateAs<GeodesicsStage>("geodesics", YAML::Load("{type: dijkstra}"), "bench", "geodesics")
          ->Prepare(in->surface)
          ->Distances(in->samples);
  const EmbeddingInput e{in->surface, in->samples, in->D};
  in->Dss = SampleDistances(e);
  in->init = LsmdsInitialConfiguration(e, in->Dss, LsmdsOptions{});
  return in;
}

// Inputs by (figure vertices, samples), built on first use.
const Input& GetInput(int vertices, int samples) {
  static std::map<std::pair<int, int>, std::unique_ptr<Input>> cache;
  auto& slot = cache[{vertices, samples}];
  if (!slot) slot = MakeInput(Figure(vertices), samples);
  return *slot;
}

void BM_Embedding(benchmark::State& state, const std::string& type) {
  const Input& in = GetInput(5000, static_cast<int>(state.range(0)));
  const auto stage = Builtins().CreateAs<EmbeddingStage>(
      "embedding", YAML::Load("{type: " + type + "}"), "bench", "embedding");
  EmbeddingResult r;
  for (auto _ : state) {
    r = stage->Run({in.surface, in.samples, in.D});
    benchmark::DoNotOptimize(r.Y.data());
  }
  state.counters["iterations"] = r.status.iterations;
  state.counters["stress"] = r.normalized_stress;
  state.counters["vertices"] = in.surface.NumVertices();
}

void BM_Smacof(benchmark::State& state) {
  const Input& in = GetInput(5000, static_cast<int>(state.range(0)));
  SmacofResult r;
  for (auto _ : state) {
    r = Smacof(in.Dss, in.init);
    benchmark::DoNotOptimize(r.X.data());
  }
  state.counters["iterations"] = r.iterations;
  state.counters["evaluations"] = r.evaluations;
  state.counters["stress"] = r.normalized_stress;
  state.counters["converged"] = r.converged;
}
BENCHMARK(BM_Smacof)->Arg(500)->Arg(1000)->Arg(2000)->MeasureProcessCPUTime()->UseRealTime()->Unit(
    benchmark::kMillisecond);

void BM_ClassicalMds(benchmark::State& state) {
  const Input& in = GetInput(5000, static_cast<int>(state.range(0)));
  for (auto _ : state) {
    ClassicalMdsResult r = ClassicalMds(in.Dss);
    benchmark::DoNotOptimize(r.X.data());
  }
}
BENCHMARK(BM_ClassicalMds)
    ->Arg(500)
    ->Arg(1000)
    ->Arg(2000)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_OutOfSample(benchmark::State& state) {
  const Input& in = GetInput(static_cast<int>(state.range(0)), 1000);
  static std::map<int, Eigen::MatrixXd> embedded;  // SMACOF of the samples, once per figure
  auto it = embedded.find(static_cast<int>(state.range(0)));
  if (it == embedded.end()) {
    it = embedded.emplace(static_cast<int>(state.range(0)), Smacof(in.Dss, in.init).X).first;
  }
  const std::vector<int> rest = NonSampleVertices({in.surface, in.samples, in.D});
  for (auto _ : state) {
    Eigen::MatrixXd Y = PlaceOutOfSample(it->second, in.D, rest);
    benchmark::DoNotOptimize(Y.data());
  }
  state.counters["vertices"] = in.surface.NumVertices();
  state.counters["placed"] = static_cast<double>(rest.size());
}
BENCHMARK(BM_OutOfSample)
    ->Arg(5000)
    ->Arg(50000)
    ->MeasureProcessCPUTime()
    ->UseRealTime()
    ->Unit(benchmark::kMillisecond);

void BM_SmacofTosca(benchmark::State& state, const std::string& shape) {
  const std::string root = testing::DataRoot();
  if (root.empty()) {
    state.SkipWithError("no TOSCA data (set SYMEMBED_DATA)");
    return;
  }
  static std::map<std::string, std::unique_ptr<Input>> cache;
  auto& in = cache[shape];
  if (!in) in = MakeInput(LoadSurface(root + "/tosca_iso_5k/shapes/" + shape + ".off"), 1000);
  SmacofResult r;
  for (auto _ : state) {
    r = Smacof(in->Dss, in->init);
    benchmark::DoNotOptimize(r.X.data());
  }
  state.counters["iterations"] = r.iterations;
  state.counters["evaluations"] = r.evaluations;
  state.counters["stress"] = r.normalized_stress;
}

// Every registered embedding stage on the same inputs.
const bool registered = [] {
  for (const std::string& type : Builtins().Names("embedding")) {
    benchmark::RegisterBenchmark(("BM_Embedding/" + type).c_str(), BM_Embedding, type)
        ->Arg(500)
        ->Arg(1000)
        ->Arg(2000)
        ->MeasureProcessCPUTime()
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  for (const std::string shape : {"cat0", "david0", "michael0"}) {
    benchmark::RegisterBenchmark(("BM_SmacofTosca/" + shape).c_str(), BM_SmacofTosca, shape)
        ->MeasureProcessCPUTime()
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
}  // namespace symembed

BENCHMARK_MAIN();

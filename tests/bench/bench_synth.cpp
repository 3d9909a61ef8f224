// The synthetic benchmark generator (wall-clock; poses run on all cores).
//
//   BM_SynthRestShape/<kind>/<vertices>  box model + Catmull-Clark + mirror map + weights
//   BM_SynthClass/<kind>/<vertices>      rest shape and 8 poses (GenerateClass, no options)
//   BM_SynthRemesh/<vertices>            one pose decimated to 40 % of its vertices
//   BM_SynthWriteDataset                 `symembed synth --kind humanoid --poses 8` (5k vertices,
//                                        files written to a temporary folder)
#include <benchmark/benchmark.h>

#include "eval/synthetic/posing.h"
#include "eval/synthetic/synthetic.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

void BM_SynthRestShape(benchmark::State& state, FigureKind kind) {
  for (auto _ : state) {
    RestFigure rest = MakeRestFigure(kind, static_cast<int>(state.range(0)));
    benchmark::DoNotOptimize(rest.surface.V.data());
    state.counters["vertices"] = rest.surface.NumVertices();
  }
}
BENCHMARK_CAPTURE(BM_SynthRestShape, humanoid, FigureKind::kHumanoid)
    ->Arg(1000)->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_SynthRestShape, quadruped, FigureKind::kQuadruped)
    ->Arg(5000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SynthClass(benchmark::State& state, FigureKind kind) {
  SynthOptions options;
  options.kinds = {kind};
  options.poses = 8;
  options.vertices = static_cast<int>(state.range(0));
  for (auto _ : state) {
    SynthClass c = GenerateClass(kind, options);
    benchmark::DoNotOptimize(c.shapes.data());
  }
}
BENCHMARK_CAPTURE(BM_SynthClass, humanoid, FigureKind::kHumanoid)
    ->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_SynthClass, quadruped, FigureKind::kQuadruped)
    ->Arg(5000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SynthRemesh(benchmark::State& state) {
  const RestFigure rest = MakeRestFigure(FigureKind::kHumanoid, static_cast<int>(state.range(0)));
  TrackedSurface posed;
  posed.surface = Surface{SkinVertices(rest, RandomPose(rest.figure.bones, 7, 0.0, 0)),
                          rest.surface.F};
  for (int i = 0; i < rest.surface.NumVertices(); ++i) posed.rest_ids.push_back(i);
  const int target = rest.surface.NumVertices() * 2 / 5;
  for (auto _ : state) {
    TrackedSurface r = Remesh(posed, target, 3);
    benchmark::DoNotOptimize(r.surface.V.data());
  }
}
BENCHMARK(BM_SynthRemesh)->Arg(5000)->Arg(20000)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SynthWriteDataset(benchmark::State& state) {
  testing::TempDir dir;
  SynthOptions options;  // humanoid, 8 poses, 5k vertices
  int run = 0;
  for (auto _ : state) {
    WriteSyntheticDataset(dir.File("run" + std::to_string(run++)), options);
  }
}
BENCHMARK(BM_SynthWriteDataset)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace symembed

BENCHMARK_MAIN();

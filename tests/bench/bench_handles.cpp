// Cutting the handles of glued synthetic bodies (core/handles.h), one thread.
//
//   BM_CutHandles/<kind>/<pose>  CutHandles on pose <pose> of the synthetic benchmark's glued
//                                poses (configs/bench/synthetic_failures.yaml: 5k vertices,
//                                glue 0.5, seed 1); the counters give the genus and the cuts
//   BM_CutHandlesGenusZero       the same surface call on an unglued pose (genus 0: the cost
//                                every shape of a set without topological noise pays)
#include <benchmark/benchmark.h>

#include <map>

#include "core/handles.h"
#include "eval/synthetic/synthetic.h"

namespace symembed {
namespace {

const SynthClass& Glued(FigureKind kind) {
  static std::map<FigureKind, SynthClass> cache;
  auto it = cache.find(kind);
  if (it == cache.end()) {
    SynthOptions o;
    o.kinds = {kind};
    o.poses = 10;
    o.vertices = 5000;
    o.glue = 0.5;
    it = cache.emplace(kind, GenerateClass(kind, o)).first;
  }
  return it->second;
}

void BM_CutHandles(benchmark::State& state) {
  const FigureKind kind = static_cast<FigureKind>(state.range(0));
  const Surface& s = Glued(kind).shapes[state.range(1)].shape.surface;
  HandleCutResult r;
  for (auto _ : state) {
    r = CutHandles(s);
    benchmark::DoNotOptimize(r.F.data());
  }
  state.counters["genus"] = r.genus_before;
  state.counters["cuts"] = r.cuts;
  state.counters["vertices"] = s.NumVertices();
}
// Glued poses of seed 1: humanoid 1, 2, 3, 8, 9; quadruped 0, 2, 5, 7, 9.
BENCHMARK(BM_CutHandles)
    ->ArgNames({"kind", "pose"})
    ->Args({0, 2})
    ->Args({0, 8})
    ->Args({1, 0})
    ->Args({1, 2})
    ->Args({1, 5})
    ->Args({1, 9})
    ->Unit(benchmark::kMillisecond);

void BM_CutHandlesGenusZero(benchmark::State& state) {
  const Surface& s = Glued(FigureKind::kHumanoid).shapes[0].shape.surface;
  for (auto _ : state) benchmark::DoNotOptimize(CutHandles(s).F.data());
}
BENCHMARK(BM_CutHandlesGenusZero)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace symembed

BENCHMARK_MAIN();

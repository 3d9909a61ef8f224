// Per-pair stages (flip scorers, matching) and the symmetry / symmetrize / canonical-frame steps
// on a mirror-symmetric figure (tests/test_util.h SymmetricFigure, detail 5: about 4.8k
// vertices, the size of the TOSCA 5k meshes) and a second pose of it. The figure's own
// coordinates stand in for the embeddings (time depends on #V, not on the values).
//
//   BM_Flip/<scorer>            FlipStage::Run on one pair (per-shape data prepared outside);
//                               extrinsic_300_samples, extrinsic_all_target_vertices: the
//                               orientation term with 300 source samples, on every target vertex
//   BM_FlipPrepare/<scorer>     ComputeNeeds of FlipStage::Needs on one shape
//   BM_Matching/<matcher>       MatchingStage::Run on one pair
//   BM_Symmetry/<stage>         SymmetryStage::Run, 1,000 samples (Euclidean distances)
//   BM_Symmetrize/<stage>       SymmetrizeStage::Run, 1,000 samples (ceres_without_warm_start:
//                               100 Levenberg-Marquardt iterations from the embedding)
//   BM_CanonicalFrame           CanonicalFrame of one shape
//   BM_Nearest3d/<hint>/<k>     NearestKd<3>: every source vertex of the canonical frame, turned by
//                               candidate k, among the target's (a flip candidate map), with or
//                               without the previous query's answer as the hint
#include <benchmark/benchmark.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "core/canonical_frame.h"
#include "core/fmap/functional_map.h"
#include "core/nearest_kd.h"
#include "harness/pair_pipeline.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

constexpr int kDetail = 5;
constexpr int kSamples = 1000;

struct Pair {
  ShapeData source, target;
  PreprocessedGroundTruth gt;
  std::vector<int> samples;
  Eigen::MatrixXd D;  // #S x #V Euclidean distances of the source
  SymmetryResult symmetry;
};

const Pair& TestPair() {
  static const Pair pair = [] {
    Pair p;
    p.source.name = "rest";
    p.source.surface = testing::SymmetricFigure(kDetail);
    p.source.Y = CanonicalFrame(p.source.surface.V);
    p.target.name = "posed";
    p.target.surface = testing::PosedSymmetricFigure(kDetail, 0.5, 0.2);
    p.target.Y = CanonicalFrame(p.target.surface.V);
    const int n = p.source.surface.NumVertices();
    for (int i = 0; i < n; ++i) {
      p.gt.source_ids.push_back(i);
      p.gt.target_ids.push_back(i);
    }
    for (int s = 0; s < kSamples; ++s) p.samples.push_back(static_cast<int>(1LL * s * n / kSamples));
    // The extrinsic scorer's orientation term runs on the shapes' own samples, which are
    // farthest-point samples in the pipeline (a prefix of them covers the surface).
    p.source.samples = EuclideanFarthestPoints(p.source.surface.V, kSamples);
    p.target.samples = EuclideanFarthestPoints(p.target.surface.V, kSamples);
    const Eigen::MatrixX3d& V = p.source.surface.V;
    p.D.resize(kSamples, n);
    for (int s = 0; s < kSamples; ++s) {
      p.D.row(s) = (V.rowwise() - V.row(p.samples[s])).rowwise().norm().transpose();
    }
    return p;
  }();
  return pair;
}

// A stage from its options, e.g. "{type: extrinsic, terms: {descriptor: {weight: 0}}}".
template <typename T>
std::unique_ptr<T> Make(const Registry& registry, const std::string& kind,
                        const std::string& yaml) {
  return registry.CreateAs<T>(kind, YAML::Load(yaml), "bench", kind);
}

std::string Type(const std::string& name) { return "{type: " + name + "}"; }

void BM_Flip(benchmark::State& state, const Registry* registry, std::string yaml) {
  const auto stage = Make<FlipStage>(*registry, "flip", yaml);
  Pair p = TestPair();
  ComputeNeeds(stage->Needs(), &p.source);
  ComputeNeeds(stage->Needs(), &p.target);
  for (auto _ : state) {
    FlipResult r = stage->Run(PairInput{p.source, p.target, &p.gt});
    benchmark::DoNotOptimize(r.chosen);
  }
  state.counters["vertices"] = p.source.surface.NumVertices();
}

void BM_FlipPrepare(benchmark::State& state, const Registry* registry, std::string name) {
  const auto stage = Make<FlipStage>(*registry, "flip", Type(name));
  for (auto _ : state) {
    ShapeData shape = TestPair().source;
    ComputeNeeds(stage->Needs(), &shape);
    benchmark::DoNotOptimize(shape.products.size());
  }
}

void BM_Matching(benchmark::State& state, const Registry* registry, std::string name) {
  const auto stage = Make<MatchingStage>(*registry, "matching", Type(name));
  const Pair& p = TestPair();
  const EmbeddedPoints source = EmbeddedShape(p.source), target = EmbeddedShape(p.target);
  for (auto _ : state) {
    MatchResult r = stage->Run(source, target);
    benchmark::DoNotOptimize(r.map.data());
  }
}

void BM_Symmetry(benchmark::State& state, const Registry* registry, std::string name) {
  const auto stage = Make<SymmetryStage>(*registry, "symmetry", Type(name));
  const Pair& p = TestPair();
  EmbeddingResult embedding;
  embedding.Y = p.source.surface.V;
  for (auto _ : state) {
    SymmetryResult r = stage->Run(SymmetryInput{p.source.surface, p.samples, p.D, embedding});
    benchmark::DoNotOptimize(r.normal.data());
  }
}

void BM_Symmetrize(benchmark::State& state, const Registry* registry, std::string yaml) {
  const Pair& p = TestPair();
  EmbeddingResult embedding;
  embedding.Y = p.source.surface.V;
  const SymmetryInput input{p.source.surface, p.samples, p.D, embedding};
  const SymmetryResult symmetry =
      Make<SymmetryStage>(*registry, "symmetry", Type("plane3d"))->Run(input);
  const auto stage = Make<SymmetrizeStage>(*registry, "symmetrize", yaml);
  for (auto _ : state) {
    SymmetrizeResult r = stage->Run(input, symmetry);
    benchmark::DoNotOptimize(r.Y.data());
  }
}

void BM_CanonicalFrame(benchmark::State& state) {
  const Pair& p = TestPair();
  for (auto _ : state) {
    Eigen::MatrixX3d C = CanonicalFrame(p.source.surface.V);
    benchmark::DoNotOptimize(C.data());
  }
}
BENCHMARK(BM_CanonicalFrame)->Unit(benchmark::kMillisecond);

void BM_Nearest3d(benchmark::State& state, bool hint) {
  const Pair& p = TestPair();
  const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> points = p.target.Y;
  const NearestKd<3> tree(points.data(), static_cast<int>(points.rows()));
  const Eigen::MatrixX3d Q = p.source.Y * CandidateRotations()[state.range(0)];
  for (auto _ : state) {
    int previous = -1;
    for (int r = 0; r < Q.rows(); ++r) {
      const double q[3] = {Q(r, 0), Q(r, 1), Q(r, 2)};
      double sq = 0.0;
      previous = tree.Nearest(q, &sq, hint ? previous : -1);
    }
    benchmark::DoNotOptimize(previous);
  }
}
BENCHMARK_CAPTURE(BM_Nearest3d, no_hint, false)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Nearest3d, hint, true)->DenseRange(0, 3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace symembed

int main(int argc, char** argv) {
  using namespace symembed;
  static Registry registry;
  RegisterBuiltinStages(registry);
  for (const std::string& name : registry.Names("flip")) {
    benchmark::RegisterBenchmark(("BM_Flip/" + name).c_str(), BM_Flip, &registry,
                                 Type(name))
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_FlipPrepare/" + name).c_str(), BM_FlipPrepare, &registry,
                                 name)
        ->Unit(benchmark::kMillisecond);
  }
  // The orientation term on every target vertex instead of the target's samples.
  benchmark::RegisterBenchmark("BM_Flip/extrinsic_all_target_vertices", BM_Flip, &registry,
                               "{type: extrinsic, terms: {orientation: {zoomout: {target_samples: 0}}}}")
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_Flip/extrinsic_300_samples", BM_Flip, &registry,
                               "{type: extrinsic, terms: {orientation: {zoomout: {samples: 300}}}}")
      ->Unit(benchmark::kMillisecond);
  // Each added part's cost: the scorer without it.
  for (const auto& [name, off] : std::vector<std::pair<std::string, std::string>>{
           {"refined", "decide: {type: argmin}"},
           {"orientation", "terms: {orientation: {weight: 0}}"},
           {"descriptor", "terms: {descriptor: {weight: 0}}"}}) {
    benchmark::RegisterBenchmark(("BM_Flip/extrinsic_no_" + name).c_str(), BM_Flip, &registry,
                                 "{type: extrinsic, " + off + "}")
        ->Unit(benchmark::kMillisecond);
  }
  for (const std::string& name : registry.Names("matching")) {
    benchmark::RegisterBenchmark(("BM_Matching/" + name).c_str(), BM_Matching, &registry, name)
        ->Unit(benchmark::kMillisecond);
  }
  for (const std::string& name : registry.Names("symmetry")) {
    benchmark::RegisterBenchmark(("BM_Symmetry/" + name).c_str(), BM_Symmetry, &registry, name)
        ->Unit(benchmark::kMillisecond);
  }
  for (const std::string& name : registry.Names("symmetrize")) {
    benchmark::RegisterBenchmark(("BM_Symmetrize/" + name).c_str(), BM_Symmetrize, &registry,
                                 Type(name))
        ->Unit(benchmark::kMillisecond);
  }
  // Levenberg-Marquardt alone, as before the warm start became the default.
  benchmark::RegisterBenchmark("BM_Symmetrize/ceres_without_warm_start", BM_Symmetrize, &registry,
                               "{type: ceres, warm_start_iterations: 0, max_iterations: 100}")
      ->Unit(benchmark::kMillisecond);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

// Laplace-Beltrami bases and the refine stages on a ~5k-vertex near-isometric pair: the
// asymmetric blob BumpyBlob(29) (5,048 vertices) and its twisted copy with shuffled ids
// (tests/test_util.h), the map to refine being the ground truth with half of its entries moved
// up to 3 rings away. Bases are computed outside the timed loops of the refine benchmarks, as the
// runner computes them once per shape.
//
//   BM_LaplaceBasis/<k>            ComputeLaplaceBasis on the 5,048-vertex blob
//   BM_SpectralNearest/<method>/<k> build + query of all 5,048 source rows among the 5,048
//                                  target rows of the first k eigenvectors (kd-tree vs brute force)
//   BM_NearestKernel/<isa>/<k>    the brute-force kernel alone (nearest_kernel.h) on the same
//                                  rows, each instruction-set build (AVX2 skipped without it)
//   BM_Refine/<variant>            RefineStage::Run per pair; counter `error`: mean Euclidean
//                                  error / sqrt(area) after refinement (`error_before`: before).
//                                  The embedded points (the discrete stage's embedding term) are
//                                  each shape's vertex coordinates in units of the unit-area
//                                  surface, which the twisted copy keeps close
//
// When the TOSCA data is present (testing::DataRoot()), BM_RefineTosca/<variant> times the same
// variants on cat0 -> cat1 after standard preprocessing (ground truth not used: the map to
// refine is the nearest vertex in the unit-area coordinates, timing only).
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "core/fmap/nearest_kernel.h"
#include "core/fmap/spectral_knn.h"
#include "core/mesh_io.h"
#include "core/spectral.h"
#include "registry/registry.h"
#include "stages/preprocess/standard.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

struct BenchPair {
  ShapeData source, target;
  std::vector<int> truth;  // empty when unknown
  std::vector<int> initial;
  EmbeddedPoints source_points, target_points;  // vertex coordinates / sqrt(area)
};

double MeanError(const BenchPair& p, const std::vector<int>& map) {
  const Surface& t = p.target.surface;
  double sum = 0.0;
  for (size_t i = 0; i < map.size(); ++i) sum += (t.V.row(map[i]) - t.V.row(p.truth[i])).norm();
  return sum / map.size() / std::sqrt(TotalArea(t));
}

std::vector<int> Perturbed(const Surface& t, const std::vector<int>& truth, unsigned seed) {
  std::vector<std::set<int>> adjacent(t.NumVertices());
  for (int f = 0; f < t.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      adjacent[t.F(f, k)].insert(t.F(f, (k + 1) % 3));
      adjacent[t.F(f, (k + 1) % 3)].insert(t.F(f, k));
    }
  }
  std::mt19937 rng(seed);
  std::vector<int> map = truth;
  for (int& m : map) {
    if (rng() % 2) continue;
    for (int ring = 0, steps = 1 + rng() % 3; ring < steps; ++ring) {
      const std::vector<int> next(adjacent[m].begin(), adjacent[m].end());
      m = next[rng() % next.size()];
    }
  }
  return map;
}

// Bases for the largest k any variant uses, so every variant reads its leading eigenpairs; and
// the embedded points.
void Prepare(BenchPair* p) {
  p->source_points.Y = p->source.surface.V / std::sqrt(TotalArea(p->source.surface));
  p->target_points.Y = p->target.surface.V / std::sqrt(TotalArea(p->target.surface));
  ShapeNeeds needs;
  needs.basis = 120;
  ComputeNeeds(needs, &p->source);
  ComputeNeeds(needs, &p->target);
}

const BenchPair& BlobPair() {
  static const BenchPair pair = [] {
    BenchPair p;
    p.source.surface = testing::BumpyBlob(29, 3);
    p.target.surface = testing::TwistedShuffledCopy(p.source.surface, 0.1, 5, &p.truth);
    p.initial = Perturbed(p.target.surface, p.truth, 7);
    Prepare(&p);
    return p;
  }();
  return pair;
}

// cat0 -> cat1 of TOSCA iso 5k, or nullptr when the data is missing.
const BenchPair* ToscaPair() {
  static const std::unique_ptr<BenchPair> pair = []() -> std::unique_ptr<BenchPair> {
    const std::string root = testing::DataRoot();
    const std::string dir = root + "/tosca_iso_5k/shapes/";
    if (root.empty() || !std::filesystem::exists(dir + "cat0.off")) return nullptr;
    auto p = std::make_unique<BenchPair>();
    p->source.surface = StandardPreprocess(LoadSurface(dir + "cat0.off"), {}).surface;
    p->target.surface = StandardPreprocess(LoadSurface(dir + "cat1.off"), {}).surface;
    SpectralNearest tree(p->target.surface.V);
    tree.Query(p->source.surface.V, &p->initial);
    Prepare(p.get());
    return p;
  }();
  return pair.get();
}

void BM_LaplaceBasis(benchmark::State& state) {
  const Surface& s = BlobPair().source.surface;
  LaplaceBasisOptions options;
  options.k = static_cast<int>(state.range(0));
  for (auto _ : state) {
    LaplaceBasis b = ComputeLaplaceBasis(s, options);
    benchmark::DoNotOptimize(b.evecs.data());
  }
  state.counters["vertices"] = s.NumVertices();
}
BENCHMARK(BM_LaplaceBasis)->Arg(50)->Arg(120)->Arg(200)->Unit(benchmark::kMillisecond);

void BM_SpectralNearest(benchmark::State& state, SpectralNearest::Method method) {
  const BenchPair& p = BlobPair();
  const int k = static_cast<int>(state.range(0));
  const Eigen::MatrixXd source = p.source.basis.evecs.leftCols(k);
  const Eigen::MatrixXd target = p.target.basis.evecs.leftCols(k);
  std::vector<int> nearest;
  for (auto _ : state) {
    const SpectralNearest search(target, {}, method);
    search.Query(source, &nearest);
    benchmark::DoNotOptimize(nearest.data());
  }
}
BENCHMARK_CAPTURE(BM_SpectralNearest, kd_tree, SpectralNearest::Method::kKdTree)
    ->Arg(10)
    ->Arg(20)
    ->Arg(40)
    ->Arg(120)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_SpectralNearest, brute_force, SpectralNearest::Method::kBruteForce)
    ->Arg(10)
    ->Arg(20)
    ->Arg(40)
    ->Arg(120)
    ->Unit(benchmark::kMillisecond);

void BM_NearestKernel(benchmark::State& state, NearestIsa isa) {
  if (!NearestKernelSupports(isa)) {
    state.SkipWithError("this processor does not run that build");
    return;
  }
  const BenchPair& p = BlobPair();
  const int k = static_cast<int>(state.range(0));
  const Eigen::MatrixXf target = p.target.basis.evecs.leftCols(k).cast<float>();
  const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> source =
      p.source.basis.evecs.leftCols(k).cast<float>();
  const PackedPoints packed = PackPoints(target.data(), static_cast<int>(target.rows()), k,
                                         static_cast<int>(target.rows()));
  std::vector<int> nearest(source.rows());
  for (auto _ : state) {
    NearestPacked(packed, source.data(), static_cast<int>(source.rows()), nearest.data(), isa);
    benchmark::DoNotOptimize(nearest.data());
  }
  // Multiply-adds per second (one per dimension per query-point pair).
  state.counters["madd_per_s"] =
      benchmark::Counter(static_cast<double>(source.rows()) * target.rows() * k,
                         benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK_CAPTURE(BM_NearestKernel, avx512, NearestIsa::kAvx512)
    ->Arg(20)
    ->Arg(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_NearestKernel, avx2, NearestIsa::kAvx2)
    ->Arg(20)
    ->Arg(60)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_NearestKernel, baseline, NearestIsa::kBaseline)
    ->Arg(20)
    ->Arg(60)
    ->Unit(benchmark::kMillisecond);

void BM_Refine(benchmark::State& state, const BenchPair* pair, const std::string& yaml) {
  if (pair == nullptr) {
    state.SkipWithError("TOSCA data not found");
    return;
  }
  Registry registry;
  RegisterBuiltinStages(registry);
  const auto stage = registry.CreateAs<RefineStage>("refine", YAML::Load(yaml), "bench", "refine");
  // The per-shape data the runner prepares once per shape, outside the timed loop.
  ShapeData source = pair->source, target = pair->target;
  ComputeNeeds(stage->Needs(), &source);
  ComputeNeeds(stage->Needs(), &target);
  MatchResult r;
  for (auto _ : state) {
    r = stage->Run(RefineInput{{source, target}, pair->initial, &pair->source_points,
                               &pair->target_points});
    benchmark::DoNotOptimize(r.map.data());
  }
  state.counters["vertices"] = pair->source.surface.NumVertices();
  if (!pair->truth.empty()) {
    state.counters["error_before"] = MeanError(*pair, pair->initial);
    state.counters["error"] = MeanError(*pair, r.map);
  }
}

const std::vector<std::pair<std::string, std::string>>& Variants() {
  static const std::vector<std::pair<std::string, std::string>> variants = {
      {"none", "{type: none}"},
      {"icp_k50", "{type: icp}"},
      {"zoomout_dense", "{type: zoomout, sample_count: 0, extra_k_starts: []}"},
      {"zoomout_s500",
       "{type: zoomout, sample_count: 500, target_sample_count: 0, extra_k_starts: []}"},
      {"zoomout_s1000",
       "{type: zoomout, sample_count: 1000, target_sample_count: 0, extra_k_starts: []}"},
      {"zoomout_s1000_t1000",
       "{type: zoomout, sample_count: 1000, target_sample_count: 1000, extra_k_starts: []}"},
      {"zoomout_starts",
       "{type: zoomout, sample_count: 1000, target_sample_count: 1000, "
       "extra_k_starts: [10, 15]}"},
      {"zoomout", "{type: zoomout}"},
      {"discrete", "{type: discrete}"},
      {"discrete_no_embedding", "{type: discrete, weights: {embedding: 0}}"},
      {"discrete_vertices", "{type: discrete, candidates: vertices}"},
  };
  return variants;
}

const bool kRegistered = [] {
  for (const auto& [name, yaml] : Variants()) {
    benchmark::RegisterBenchmark(("BM_Refine/" + name).c_str(), [yaml = yaml](benchmark::State& s) {
      BM_Refine(s, &BlobPair(), yaml);
    })->Unit(benchmark::kMillisecond);
  }
  for (const auto& [name, yaml] : Variants()) {
    benchmark::RegisterBenchmark(("BM_RefineTosca/" + name).c_str(), [yaml = yaml](
                                                                         benchmark::State& s) {
      BM_Refine(s, ToscaPair(), yaml);
    })->Unit(benchmark::kMillisecond);
  }
  return true;
}();

}  // namespace
}  // namespace symembed

BENCHMARK_MAIN();

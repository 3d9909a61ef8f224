// Per-shape geometry stages on smooth closed blobs (tests/test_util.h BumpyBlob) of about 5k,
// 20k and 50k vertices. Wall-clock time (UseRealTime): the geodesic solvers run on all cores.
//
//   BM_Geodesics/<solver>/<n>        Prepare + Distances for 1,000 sources, n = 29 (5,048 vertices)
//   BM_GeodesicsPrepare/<solver>/<n> Prepare only (graph, stencils, factorisations)
//   BM_GeodesicsScaling/<solver>/<n> Prepare + 100 sources at 5k, 20k, 50k (Complexity)
//   BM_DijkstraQueue/<queue>/<n>     Dijkstra from 1,000 sources on one thread, with the bucket
//                                    queue (`buckets`, what Dijkstra uses) or the binary heap
//   BM_Sampling/<n>                  farthest point sampling, 1,000 samples
//   BM_Curvature/<n>                 ComputeCurvature with default options
//   BM_L1Nearest/rows/packed         L1Columns::Nearest (packed 1) or the plain loop (0), partial
//                                    matching's search: 2,000 queries against the distances of
//                                    10,000 points of a sphere to `rows` landmarks (3 rows: 300
//                                    queries against 300 points, as the triples')
//   BM_SignFlips/sweep/<0|1>         every sign flip of 8 eigenfunctions at 1,000 farthest-point
//                                    samples of the 5k blob, each flipped sample's nearest
//                                    sample: KnnIndex pattern by pattern (0) or
//                                    NearestUnderSignFlips (1), one thread
//   BM_GeodesicsTosca/<solver>       Prepare + 1,000 farthest-point sources on TOSCA cat0
//                                    (5,000 vertices, preprocessed), when the data is present
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/curvature.h"
#include "core/matching/l1_nearest.h"
#include "core/mesh_graph.h"
#include "core/mesh_io.h"
#include "core/sign_flip_nearest.h"
#include "registry/registry.h"
#include "stages/preprocess/standard.h"
#include "stages/sampling/farthest_point.h"
#include "stages/symmetry/spectral_symmetry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// Blob sizes: 6 n^2 + 2 vertices.
constexpr int kSmall = 29, kMedium = 58, kLarge = 91;

const Surface& Blob(int n) {
  static std::map<int, Surface> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, testing::BumpyBlob(n, 3)).first;
  return it->second;
}

std::vector<int> SpreadSources(int num_vertices, int count) {
  std::vector<int> sources(count);
  for (int i = 0; i < count; ++i) sources[i] = static_cast<int>(1LL * i * num_vertices / count);
  return sources;
}

std::unique_ptr<GeodesicsStage> MakeStage(const Registry& registry, const std::string& name) {
  return registry.CreateAs<GeodesicsStage>("geodesics", YAML::Load("{type: " + name + "}"),
                                           "bench", "geodesics");
}

void BM_Geodesics(benchmark::State& state, const Registry* registry, std::string name,
                  int num_sources) {
  const Surface& s = Blob(static_cast<int>(state.range(0)));
  const auto stage = MakeStage(*registry, name);
  const std::vector<int> sources = SpreadSources(s.NumVertices(), num_sources);
  for (auto _ : state) {
    const auto solver = stage->Prepare(s);
    Eigen::MatrixXd D = solver->Distances(sources);
    benchmark::DoNotOptimize(D.data());
  }
  state.counters["vertices"] = s.NumVertices();
  state.counters["sources"] = num_sources;
  state.SetComplexityN(s.NumVertices());
}

void BM_GeodesicsTosca(benchmark::State& state, const Registry* registry, std::string name,
                       const Surface* s) {
  const auto stage = MakeStage(*registry, name);
  const std::vector<int> sources = FarthestPointSampling(*s, {1000, 1}).samples;
  for (auto _ : state) {
    const auto solver = stage->Prepare(*s);
    Eigen::MatrixXd D = solver->Distances(sources);
    benchmark::DoNotOptimize(D.data());
  }
  state.counters["vertices"] = s->NumVertices();
  state.counters["sources"] = static_cast<double>(sources.size());
}

void BM_GeodesicsPrepare(benchmark::State& state, const Registry* registry, std::string name) {
  const Surface& s = Blob(static_cast<int>(state.range(0)));
  const auto stage = MakeStage(*registry, name);
  for (auto _ : state) {
    auto solver = stage->Prepare(s);
    benchmark::DoNotOptimize(solver.get());
  }
  state.counters["vertices"] = s.NumVertices();
}

void BM_DijkstraQueue(benchmark::State& state, bool buckets) {
  const Surface& s = Blob(static_cast<int>(state.range(0)));
  const MeshGraph graph = BuildMeshGraph(s);
  const std::vector<int> sources = SpreadSources(s.NumVertices(), 1000);
  DijkstraWorkspace<double> ws;
  std::vector<double> dist(s.NumVertices());
  for (auto _ : state) {
    for (const int source : sources) {
      if (buckets) Dijkstra<double>(graph, source, dist.data(), &ws);
      else DijkstraWithHeap<double>(graph, source, dist.data(), &ws);
    }
    benchmark::DoNotOptimize(dist.data());
  }
  state.counters["vertices"] = s.NumVertices();
}
BENCHMARK_CAPTURE(BM_DijkstraQueue, heap, false)->Arg(kSmall)->Arg(kMedium)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_DijkstraQueue, buckets, true)->Arg(kSmall)->Arg(kMedium)
    ->Unit(benchmark::kMillisecond);

void BM_Sampling(benchmark::State& state) {
  const Surface& s = Blob(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    SamplingResult r = FarthestPointSampling(s, {1000, 1});
    benchmark::DoNotOptimize(r.samples.data());
  }
  state.counters["vertices"] = s.NumVertices();
  state.SetComplexityN(s.NumVertices());
}
BENCHMARK(BM_Sampling)->Arg(kSmall)->Arg(kMedium)->Arg(kLarge)->Unit(benchmark::kMillisecond)
    ->Complexity();

void BM_Curvature(benchmark::State& state) {
  const Surface& s = Blob(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    CurvatureFeatures c = ComputeCurvature(s);
    benchmark::DoNotOptimize(c.mean.data());
  }
  state.counters["vertices"] = s.NumVertices();
  state.SetComplexityN(s.NumVertices());
}
BENCHMARK(BM_Curvature)->Arg(kSmall)->Arg(kMedium)->Arg(kLarge)->Unit(benchmark::kMillisecond)
    ->Complexity();

void BM_L1Nearest(benchmark::State& state) {
  const int rows = static_cast<int>(state.range(0));
  const int n = rows == 3 ? 300 : 10000;
  // Points on the unit sphere; each column: the distances of one point to the landmarks (the
  // first `rows` points), as partial matching's geodesic coordinates.
  Eigen::MatrixXd P = Eigen::MatrixXd::Random(n, 3);
  P.rowwise().normalize();
  Eigen::MatrixXd m(rows, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < rows; ++i) m(i, j) = (P.row(i) - P.row(j)).norm();
  }
  const L1Columns columns(m);
  const Eigen::MatrixXd queries =
      m.leftCols(std::min(n, 2000)) + 0.01 * Eigen::MatrixXd::Random(rows, std::min(n, 2000));
  const bool packed = state.range(1) == 1;
  for (auto _ : state) {
    long sum = 0;
    for (int q = 0; q < queries.cols(); ++q) {
      if (packed) {
        sum += columns.Nearest(queries.col(q).data()).first;
        continue;
      }
      // The plain loop over columns, for reference.
      int best = 0;
      double best_cost = std::numeric_limits<double>::infinity();
      for (int j = 0; j < n; ++j) {
        double cost = 0.0;
        for (int i = 0; i < rows && cost < best_cost; ++i)
          cost += std::abs(m(i, j) - queries(i, q));
        if (cost < best_cost) best_cost = cost, best = j;
      }
      sum += best;
    }
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_L1Nearest)
    ->ArgNames({"rows", "packed"})
    ->ArgsProduct({{3, 40}, {0, 1}})
    ->Unit(benchmark::kMillisecond);
void BM_SignFlips(benchmark::State& state) {
  const Surface& s = Blob(kSmall);
  const std::vector<int> samples = FarthestPointSampling(s, {1000, 1}).samples;
  const Eigen::MatrixXd G = SampleSpectralCoordinates(s, samples, 8);
  const KnnIndex index(G);
  const bool sweep = state.range(0) == 1;
  for (auto _ : state) {
    long sum = 0;
    if (sweep) {
      const SignFlipNeighbours n = NearestUnderSignFlips(G, index, 1);
      sum += n.nearest.back();
    } else {
      for (unsigned pattern = 1; pattern < 256u; ++pattern) {
        Eigen::MatrixXd Q = G;
        for (int d = 0; d < 8; ++d) {
          if (pattern >> d & 1u) Q.col(d) = -Q.col(d);
        }
        Eigen::VectorXd distances;
        sum += index.Nearest(Q, &distances, 1).back();
      }
    }
    benchmark::DoNotOptimize(sum);
  }
}
BENCHMARK(BM_SignFlips)->ArgName("sweep")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace symembed

int main(int argc, char** argv) {
  static symembed::Registry registry;
  symembed::RegisterBuiltinStages(registry);
  // Every registered geodesic solver on the same inputs.
  for (const std::string& name : registry.Names("geodesics")) {
    benchmark::RegisterBenchmark(("BM_Geodesics/" + name).c_str(), symembed::BM_Geodesics,
                                 &registry, name, 1000)
        ->Arg(symembed::kSmall)->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark(("BM_GeodesicsPrepare/" + name).c_str(),
                                 symembed::BM_GeodesicsPrepare, &registry, name)
        ->Arg(symembed::kSmall)->Arg(symembed::kMedium)->Arg(symembed::kLarge)
        ->Unit(benchmark::kMillisecond)->UseRealTime();
    benchmark::RegisterBenchmark(("BM_GeodesicsScaling/" + name).c_str(), symembed::BM_Geodesics,
                                 &registry, name, 100)
        ->Arg(symembed::kSmall)->Arg(symembed::kMedium)->Arg(symembed::kLarge)
        ->Unit(benchmark::kMillisecond)->UseRealTime()->Complexity();
  }
  const std::string tosca = symembed::testing::DataRoot() + "/tosca_iso_5k/shapes/cat0.off";
  static symembed::Surface cat;
  if (!symembed::testing::DataRoot().empty() && std::filesystem::exists(tosca)) {
    cat = symembed::StandardPreprocess(symembed::LoadSurface(tosca)).surface;
    for (const std::string& name : registry.Names("geodesics")) {
      benchmark::RegisterBenchmark(("BM_GeodesicsTosca/" + name).c_str(),
                                   symembed::BM_GeodesicsTosca, &registry, name, &cat)
          ->Unit(benchmark::kMillisecond)->UseRealTime();
    }
  }
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}

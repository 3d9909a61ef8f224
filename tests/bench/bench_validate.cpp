// Mesh loading and validation speed on a TOSCA-sized mesh (about 5,000 vertices).
//
// BM_Load/<ext>: parse a file written by SaveMesh (BumpyBlob(29): 5,048 vertices, 10,092 faces)
// from memory. BM_LoadToscaOff: load every TOSCA OFF file from disk (skipped without the data).
// BM_ValidateMesh: the full validation report of the same mesh.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "core/mesh_io.h"
#include "core/validation.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

const Surface& Blob() {
  static const Surface s = testing::BumpyBlob(29, 3);
  return s;
}

void BM_Load(benchmark::State& state, const std::string& ext) {
  testing::TempDir dir;
  SaveMesh(dir.File("m." + ext), Blob());
  const std::string data = testing::ReadText(dir.File("m." + ext));
  for (auto _ : state) {
    Surface s = ParseMesh(data, ext, "m." + ext);
    benchmark::DoNotOptimize(s.V.data());
  }
  state.counters["vertices"] = Blob().NumVertices();
}
BENCHMARK_CAPTURE(BM_Load, off, std::string("off"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Load, obj, std::string("obj"))->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Load, ply, std::string("ply"))->Unit(benchmark::kMillisecond);

void BM_LoadToscaOff(benchmark::State& state) {
  const std::string root = testing::DataRoot();
  std::vector<std::string> files;
  if (!root.empty()) {
    for (const auto& e : std::filesystem::directory_iterator(root + "/tosca_iso_5k/shapes")) {
      if (e.path().extension() == ".off") files.push_back(e.path().string());
    }
  }
  if (files.empty()) {
    state.SkipWithError("TOSCA data not found (set SYMEMBED_DATA)");
    return;
  }
  for (auto _ : state) {
    for (const auto& f : files) benchmark::DoNotOptimize(LoadSurface(f).V.data());
  }
  state.counters["files"] = static_cast<double>(files.size());
}
BENCHMARK(BM_LoadToscaOff)->Unit(benchmark::kMillisecond);

void BM_ValidateMesh(benchmark::State& state) {
  for (auto _ : state) {
    MeshReport r = ValidateMesh(Blob(), "blob");
    benchmark::DoNotOptimize(r.num_edges);
  }
}
BENCHMARK(BM_ValidateMesh)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace symembed

BENCHMARK_MAIN();

// The embedding report on TOSCA: for every shape of tosca_iso_5k, preprocess (`standard`),
// 1,000 farthest-point samples (seed 1), `dijkstra` geodesics, then each embedding variant;
// per variant the mean normalised stress, iterations, wall time per shape, how many did not
// converge, and how many embeddings are reflected (det of the Procrustes fit from the sample
// coordinates to the embedding < 0).
//
// Usage: bench_embedding_tosca [--data ROOT] [--samples N] [--shapes PREFIX] [--csv FILE]
//                              [--variant YAML]...
// ROOT defaults to testing::DataRoot(); the default variants are lsmds (init original),
// lsmds with init isomap, isomap, and isomap with fix_orientation. Prints a Markdown table; with
// --csv also writes one line per (shape, variant). Exit code 2 when the data is missing.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "core/mesh_io.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

struct Totals {
  int shapes = 0, reflected = 0, unconverged = 0;
  double stress = 0.0, iterations = 0.0, seconds = 0.0, max_stress = 0.0;
};

double Seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

int Main(int argc, char** argv) {
  std::string root = testing::DataRoot(), prefix, csv_path;
  int samples = 1000;
  std::vector<std::string> variants;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw ConfigError(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--data") root = value();
    else if (arg == "--samples") samples = std::stoi(value());
    else if (arg == "--shapes") prefix = value();
    else if (arg == "--csv") csv_path = value();
    else if (arg == "--variant") variants.push_back(value());
    else throw ConfigError("unknown argument " + arg);
  }
  if (variants.empty()) {
    variants = {"{type: lsmds}", "{type: lsmds, init: isomap}", "{type: isomap}",
                "{type: isomap, fix_orientation: true}"};
  }
  const std::string dir = root + "/tosca_iso_5k/shapes";
  if (root.empty() || !std::filesystem::is_directory(dir)) {
    std::cerr << "no TOSCA data at '" << dir << "' (set SYMEMBED_DATA or pass --data)\n";
    return 2;
  }
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const std::string stem = entry.path().stem().string();
    if (entry.path().extension() == ".off" && stem.rfind(prefix, 0) == 0) names.push_back(stem);
  }
  std::sort(names.begin(), names.end());

  Registry registry;
  RegisterBuiltinStages(registry);
  auto preprocess = registry.CreateAs<PreprocessStage>("preprocess", YAML::Load("{}"), "report",
                                                       "preprocess", "standard");
  auto sampling = registry.CreateAs<SamplingStage>(
      "sampling", YAML::Load("{type: farthest_point, seed: 1, count: " + std::to_string(samples) +
                             "}"),
      "report", "sampling");
  auto geodesics = registry.CreateAs<GeodesicsStage>("geodesics", YAML::Load("{type: dijkstra}"),
                                                     "report", "geodesics");
  std::vector<std::unique_ptr<EmbeddingStage>> stages;
  for (const std::string& v : variants) {
    stages.push_back(registry.CreateAs<EmbeddingStage>("embedding", YAML::Load(v), "report",
                                                       "embedding"));
  }
  std::ofstream csv;
  if (!csv_path.empty()) {
    csv.open(csv_path);
    csv << "shape,vertices,variant,normalized_stress,iterations,converged,reflection,seconds\n";
  }
  std::vector<Totals> totals(variants.size());
  double prep_seconds = 0.0;
  for (const std::string& name : names) {
    auto start = std::chrono::steady_clock::now();
    const Surface surface = preprocess->Run(LoadSurface(dir + "/" + name + ".off")).surface;
    const std::vector<int> ids = sampling->Run(surface).samples;
    const Eigen::MatrixXd D = geodesics->Prepare(surface)->Distances(ids);
    prep_seconds += Seconds(start);
    std::cerr << name << " (" << surface.NumVertices() << " vertices):";
    for (size_t k = 0; k < stages.size(); ++k) {
      start = std::chrono::steady_clock::now();
      const EmbeddingResult r = stages[k]->Run({surface, ids, D});
      const double seconds = Seconds(start);
      Totals& t = totals[k];
      ++t.shapes;
      t.stress += r.normalized_stress;
      t.max_stress = std::max(t.max_stress, r.normalized_stress);
      t.iterations += r.status.iterations;
      t.seconds += seconds;
      t.reflected += r.reflection < 0;
      t.unconverged += !r.status.converged;
      std::cerr << " [" << k << "] " << r.normalized_stress << " " << r.status.iterations
                << (r.reflection < 0 ? " R" : "");
      if (csv.is_open()) {
        csv << name << "," << surface.NumVertices() << ",\"" << variants[k] << "\","
            << r.normalized_stress << "," << r.status.iterations << ","
            << r.status.converged << "," << r.reflection << "," << seconds << "\n";
      }
    }
    std::cerr << "\n";
  }
  std::printf("TOSCA tosca_iso_5k: %zu shapes, %d FPS samples (seed 1), dijkstra; "
              "preprocess+sampling+geodesics %.2f s per shape\n\n",
              names.size(), samples, names.empty() ? 0.0 : prep_seconds / names.size());
  std::printf("| variant | mean normalized stress | max | mean iterations | not converged | "
              "time per shape (s) | reflected |\n|---|---|---|---|---|---|---|\n");
  for (size_t k = 0; k < variants.size(); ++k) {
    const Totals& t = totals[k];
    const double n = std::max(1, t.shapes);
    std::printf("| `%s` | %.4f | %.4f | %.1f | %d | %.3f | %d / %d |\n", variants[k].c_str(),
                t.stress / n, t.max_stress, t.iterations / n, t.unconverged, t.seconds / n,
                t.reflected, t.shapes);
  }
  return 0;
}

}  // namespace
}  // namespace symembed

int main(int argc, char** argv) {
  try {
    return symembed::Main(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "bench_embedding_tosca: " << e.what() << "\n";
    return 1;
  }
}

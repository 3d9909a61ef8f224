// The embedding report on TOSCA: for every shape of tosca_iso_5k, preprocess (`standard`),
// 1,000 farthest-point samples (seed 1), `dijkstra` geodesics, then each embedding variant;
// per variant the mean normalised stress, iterations, wall and process CPU time per shape, how many
// did not converge, how many embeddings are reflected (det of the Procrustes fit from the sample
// coordinates to the embedding < 0), how many of those fits are ill-conditioned (smallest over
// largest singular value of the cross-covariance < 0.02, where the sign says little), and the
// mean fraction of samples whose neighbourhood (30 geodesically nearest samples) is reflected
// by its own Procrustes fit.
//
// Usage: bench_embedding_tosca [--data ROOT] [--samples N] [--shapes PREFIX] [--csv FILE]
//                              [--variant YAML]...
// ROOT defaults to testing::DataRoot(); the default variants are lsmds (init original),
// lsmds with init isomap, isomap, and isomap with fix_orientation. Prints a Markdown table; with
// --csv also writes one line per (shape, variant). Exit code 2 when the data is missing.
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include "core/mesh_io.h"
#include "core/procrustes.h"
#include "registry/registry.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

struct Totals {
  int shapes = 0, reflected = 0, unconverged = 0, ill_conditioned = 0;
  double stress = 0.0, iterations = 0.0, seconds = 0.0, cpu_seconds = 0.0, max_stress = 0.0,
         local = 0.0;
  std::vector<std::string> reflected_names;
};

constexpr double kIllConditioned = 0.02;
constexpr int kNeighbourhood = 30;

// Fraction of samples whose k geodesically nearest samples (itself included) are mapped from
// X to Y by a reflection: sign det(Xc^T Yc) < 0 over the neighbourhood.
double LocallyReflectedFraction(const Eigen::MatrixXd& X, const Eigen::MatrixXd& Y,
                                const Eigen::MatrixXd& Dss) {
  const int n = static_cast<int>(X.rows());
  const int k = std::min(kNeighbourhood, n);
  int reflected = 0;
  std::vector<int> order(n);
  Eigen::MatrixXd A(k, 3), B(k, 3);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) order[j] = j;
    std::partial_sort(order.begin(), order.begin() + k, order.end(),
                      [&](int a, int b) { return Dss(i, a) < Dss(i, b); });
    for (int t = 0; t < k; ++t) {
      A.row(t) = X.row(order[t]);
      B.row(t) = Y.row(order[t]);
    }
    A.rowwise() -= A.colwise().mean();
    B.rowwise() -= B.colwise().mean();
    reflected += (A.transpose() * B).determinant() < 0;
  }
  return static_cast<double>(reflected) / n;
}

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
    if (arg == "--data")
      root = value();
    else if (arg == "--samples")
      samples = std::stoi(value());
    else if (arg == "--shapes")
      prefix = value();
    else if (arg == "--csv")
      csv_path = value();
    else if (arg == "--variant")
      variants.push_back(value());
    else
      throw ConfigError("unknown argument " + arg);
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
      "sampling",
      YAML::Load("{type: farthest_point, seed: 1, count: " + std::to_string(samples) + "}"),
      "report", "sampling");
  auto geodesics = registry.CreateAs<GeodesicsStage>("geodesics", YAML::Load("{type: dijkstra}"),
                                                     "report", "geodesics");
  std::vector<std::unique_ptr<EmbeddingStage>> stages;
  for (const std::string& v : variants) {
    stages.push_back(
        registry.CreateAs<EmbeddingStage>("embedding", YAML::Load(v), "report", "embedding"));
  }
  std::ofstream csv;
  if (!csv_path.empty()) {
    csv.open(csv_path);
    csv << "shape,vertices,variant,normalized_stress,iterations,converged,reflection,"
           "conditioning,locally_reflected,seconds\n";
  }
  std::vector<Totals> totals(variants.size());
  double prep_seconds = 0.0;
  for (const std::string& name : names) {
    auto start = std::chrono::steady_clock::now();
    const Surface surface = preprocess->Run(LoadSurface(dir + "/" + name + ".off")).surface;
    const std::vector<int> ids = sampling->Run(surface).samples;
    const Eigen::MatrixXd D = geodesics->Prepare(surface)->Distances(ids);
    prep_seconds += Seconds(start);
    const int ns = static_cast<int>(ids.size());
    Eigen::MatrixXd X(ns, 3), Dss(ns, ns);
    for (int i = 0; i < ns; ++i) X.row(i) = surface.V.row(ids[i]);
    for (int j = 0; j < ns; ++j) Dss.col(j) = D.col(ids[j]);
    std::cerr << name << " (" << surface.NumVertices() << " vertices):";
    for (size_t k = 0; k < stages.size(); ++k) {
      start = std::chrono::steady_clock::now();
      const std::clock_t cpu_start = std::clock();
      const EmbeddingResult r = stages[k]->Run({surface, ids, D});
      const double seconds = Seconds(start);
      const double cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
      Eigen::MatrixXd Ys(ns, r.Y.cols());
      for (int i = 0; i < ns; ++i) Ys.row(i) = r.Y.row(ids[i]);
      const double conditioning = Ys.cols() == 3 ? FitProcrustes(X, Ys).conditioning : 0.0;
      const double local = Ys.cols() == 3 ? LocallyReflectedFraction(X, Ys, Dss) : 0.0;
      Totals& t = totals[k];
      t.ill_conditioned += conditioning < kIllConditioned;
      t.local += local;
      if (r.reflection < 0) t.reflected_names.push_back(name);
      ++t.shapes;
      t.stress += r.normalized_stress;
      t.max_stress = std::max(t.max_stress, r.normalized_stress);
      t.iterations += r.status.iterations;
      t.seconds += seconds;
      t.cpu_seconds += cpu_seconds;
      t.reflected += r.reflection < 0;
      t.unconverged += !r.status.converged;
      std::cerr << " [" << k << "] " << r.normalized_stress << " " << r.status.iterations
                << (r.reflection < 0 ? " R" : "");
      if (csv.is_open()) {
        csv << name << "," << surface.NumVertices() << ",\"" << variants[k] << "\","
            << r.normalized_stress << "," << r.status.iterations << "," << r.status.converged << ","
            << r.reflection << "," << conditioning << "," << local << "," << seconds << "\n";
      }
    }
    std::cerr << "\n";
  }
  std::printf(
      "TOSCA tosca_iso_5k: %zu shapes, %d FPS samples (seed 1), dijkstra; "
      "preprocess+sampling+geodesics %.2f s per shape\n\n",
      names.size(), samples, names.empty() ? 0.0 : prep_seconds / names.size());
  std::printf(
      "| variant | mean normalized stress | max | mean iterations | not converged | "
      "wall / CPU s per shape | reflected | ill-conditioned fits | locally reflected |\n"
      "|---|---|---|---|---|---|---|---|---|\n");
  for (size_t k = 0; k < variants.size(); ++k) {
    const Totals& t = totals[k];
    const double n = std::max(1, t.shapes);
    std::printf("| `%s` | %.4f | %.4f | %.1f | %d | %.3f / %.3f | %d / %d | %d | %.1f%% |\n",
                variants[k].c_str(), t.stress / n, t.max_stress, t.iterations / n, t.unconverged,
                t.seconds / n, t.cpu_seconds / n, t.reflected, t.shapes, t.ill_conditioned,
                100.0 * t.local / n);
  }
  std::printf("\nReflected shapes per variant:\n");
  for (size_t k = 0; k < variants.size(); ++k) {
    std::string list;
    for (const std::string& name : totals[k].reflected_names) list += " " + name;
    std::printf("- `%s`:%s\n", variants[k].c_str(), list.empty() ? " none" : list.c_str());
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

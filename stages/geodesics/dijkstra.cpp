#include "stages/geodesics/dijkstra.h"

#include "core/errors.h"

namespace symembed {

DijkstraGeodesicSolver::DijkstraGeodesicSolver(const Surface& surface,
                                               const DijkstraGeodesicsOptions& options)
    : graph_(BuildMeshGraph(surface)), options_(options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("geodesics/dijkstra: " + error);
}

Eigen::MatrixXd DijkstraGeodesicSolver::Distances(const std::vector<int>& sources) const {
  const int n = graph_.NumVertices();
  if (options_.common.precision == GeodesicPrecision::kFloat) {
    return ParallelRows(sources, n, options_.common.threads, [&](int i, double* out) {
      thread_local DijkstraWorkspace<float> ws;
      thread_local std::vector<float> dist;
      dist.resize(n);
      Dijkstra<float>(graph_, sources[i], dist.data(), &ws);
      for (int v = 0; v < n; ++v) out[v] = dist[v];
    });
  }
  return ParallelRows(sources, n, options_.common.threads, [&](int i, double* out) {
    thread_local DijkstraWorkspace<double> ws;
    Dijkstra<double>(graph_, sources[i], out, &ws);
  });
}

Eigen::MatrixXd DijkstraDistances(const Surface& surface, const std::vector<int>& sources,
                                  const DijkstraGeodesicsOptions& options) {
  return DijkstraGeodesicSolver(surface, options).Distances(sources);
}

namespace {

class DijkstraGeodesicsStage : public GeodesicsStage {
 public:
  explicit DijkstraGeodesicsStage(const DijkstraGeodesicsOptions& options) : options_(options) {}
  std::unique_ptr<GeodesicSolver> Prepare(const Surface& surface) const override {
    return std::make_unique<DijkstraGeodesicSolver>(surface, options_);
  }

 private:
  DijkstraGeodesicsOptions options_;
};

}  // namespace

void RegisterDijkstraGeodesics(Registry& registry) {
  registry.Add("geodesics", "dijkstra",
               "shortest paths on the mesh edge graph (fast, overestimates by up to ~8%)",
               [](OptionReader& reader) -> std::unique_ptr<Stage> {
                 DijkstraGeodesicsOptions options;
                 options.common = ReadGeodesicsCommonOptions(reader);
                 return std::make_unique<DijkstraGeodesicsStage>(options);
               });
}

}  // namespace symembed

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

}  // namespace symembed

#include "stages/sampling/farthest_point.h"

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "core/errors.h"
#include "core/mesh_graph.h"

namespace symembed {

SamplingResult FarthestPointSampling(const Surface& surface, const FarthestPointOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("sampling/farthest_point: " + error);
  if (surface.NumFaces() == 0)
    throw InvalidInputError("farthest point sampling: surface has no faces");
  const MeshGraph graph = BuildMeshGraph(surface);
  const int n = graph.NumVertices();
  std::vector<int> usable;
  for (int v = 0; v < n; ++v) {
    if (graph.offsets[v + 1] > graph.offsets[v]) usable.push_back(v);
  }
  SamplingResult result;
  int count = options.count;
  if (count > static_cast<int>(usable.size())) {
    count = static_cast<int>(usable.size());
    result.status.message = "count " + std::to_string(options.count) + " clamped to " +
                            std::to_string(count) + " usable vertices";
  }
  // Isolated vertices start at distance 0 so they are never the farthest.
  std::vector<double> min_dist(n, 0.0);
  for (int v : usable) min_dist[v] = std::numeric_limits<double>::infinity();
  std::mt19937 rng(options.seed);
  int next =
      usable[std::uniform_int_distribution<int>(0, static_cast<int>(usable.size()) - 1)(rng)];
  DijkstraWorkspace<double> ws;
  result.samples.reserve(count);
  for (int k = 0; k < count; ++k) {
    result.samples.push_back(next);
    DijkstraUpdateMin(graph, next, &min_dist, &ws);
    // Ties go to the lowest id, so the result depends only on the seed.
    next = static_cast<int>(std::max_element(min_dist.begin(), min_dist.end()) - min_dist.begin());
  }
  result.coverage_radius = min_dist[next];
  result.status.iterations = count;
  result.status.residual = result.coverage_radius;
  return result;
}

SamplingResult AllVerticesSampling(const Surface& surface) {
  SamplingResult result;
  result.samples.resize(surface.NumVertices());
  for (int v = 0; v < surface.NumVertices(); ++v) result.samples[v] = v;
  result.coverage_radius = 0.0;
  return result;
}

}  // namespace symembed

// Geodesic distances approximated by shortest paths on the mesh edge graph (`dijkstra`).
//
// Fast and robust (any triangle soup), but biased: paths are restricted to edges, so distances
// are overestimated, by up to about 8% on a regular grid, and the bias does not vanish under
// refinement. Use fast_marching or heat where accuracy matters.
//
// [Dijkstra 1959] A note on two problems in connexion with graphs.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/mesh_graph.h"
#include "registry/stages.h"
#include "stages/geodesics/geodesics_common.h"

namespace symembed {

struct DijkstraGeodesicsOptions {
  GeodesicsCommonOptions common;  // threads, precision

  bool IsValid(std::string* error) const { return common.IsValid(error); }
};

// Reusable solver: the edge graph is built once. Distances() returns #sources x #V graph
// distances (+infinity where unreachable), computed in parallel over sources; thread-safe.
// Throws InvalidInputError for a source id outside [0, #V).
class DijkstraGeodesicSolver : public GeodesicSolver {
 public:
  DijkstraGeodesicSolver(const Surface& surface, const DijkstraGeodesicsOptions& options = {});
  Eigen::MatrixXd Distances(const std::vector<int>& sources) const override;

 private:
  MeshGraph graph_;
  DijkstraGeodesicsOptions options_;
};

// Free-function form: #sources x #V graph distances.
Eigen::MatrixXd DijkstraDistances(const Surface& surface, const std::vector<int>& sources,
                                  const DijkstraGeodesicsOptions& options = {});

}  // namespace symembed

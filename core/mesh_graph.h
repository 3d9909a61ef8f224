// The edge graph of a triangle mesh and shortest paths on it.
//
// The graph has one node per vertex and one undirected edge per mesh edge, weighted by its
// Euclidean length. Graph distances are lengths of paths along mesh edges, so they never
// underestimate the geodesic distance; on regular meshes they overestimate it by a bounded
// factor (about 8% on a grid with diagonals, see tests/stages/geodesics_test.cpp).
//
// [Dijkstra 1959] A note on two problems in connexion with graphs.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <utility>
#include <vector>

#include "core/mesh.h"

namespace symembed {

// Compressed adjacency: the neighbours of vertex v are neighbors[offsets[v] .. offsets[v+1]),
// with edge lengths in lengths[] at the same positions. Unreferenced vertices have none.
struct MeshGraph {
  std::vector<int> offsets;     // #V + 1
  std::vector<int> neighbors;   // 2 * #E
  std::vector<double> lengths;  // 2 * #E, Euclidean edge lengths
  double min_length = 0.0;      // shortest and longest edge (0 without edges)
  double max_length = 0.0;

  int NumVertices() const { return static_cast<int>(offsets.size()) - 1; }
};

// Builds the edge graph of F (each edge once per direction, however many faces share it).
MeshGraph BuildMeshGraph(const Surface& surface);

// #sources x #V shortest-path distances on the edge graph of surface (+infinity where
// unreachable), in parallel over sources (threads: 0 = DefaultThreadCount()). Throws
// InvalidInputError for a source outside [0, #V).
Eigen::MatrixXd EdgeGraphDistances(const Surface& surface, const std::vector<int>& sources,
                                   int threads = 0);
// The same on a graph built once (BuildMeshGraph), for several calls on one surface.
Eigen::MatrixXd EdgeGraphDistances(const MeshGraph& graph, const std::vector<int>& sources,
                                   int threads = 0);

// Reusable per-thread state of Dijkstra's algorithm, so repeated calls do not allocate.
template <typename Scalar>
struct DijkstraWorkspace {
  std::vector<std::pair<Scalar, int>> heap;
  std::vector<Scalar> ball_dist;  // used by DijkstraBall: +infinity except during a call
  std::vector<std::vector<int>> buckets;  // used by Dijkstra's bucket queue
  std::vector<char> settled;
};

// Single-source shortest paths. dist: #V values, on return the graph distance from `source`
// (+infinity where unreachable): each value is the least of fl(dist[u] + length(u, v)) over the
// neighbours u, the floating-point fixed point that every label-setting order reaches.
//
// The queue is a circular array of buckets of width half the shortest edge [Dial 1969,
// Algorithm 360: shortest-path forest with topological ordering]: a relaxation from a vertex in
// bucket i lands two buckets on at least, so every vertex of the lowest bucket is final and the
// bucket is settled in any order, in constant time per vertex instead of a heap's logarithmic
// time. Where the edges' lengths differ by more than a factor of 1,000 (or an edge has length
// 0) a binary heap orders the vertices instead. Both give the same values, bit for bit.
template <typename Scalar>
void Dijkstra(const MeshGraph& graph, int source, Scalar* dist, DijkstraWorkspace<Scalar>* ws);

// The binary-heap form of Dijkstra (the same values), for tests and benchmarks.
template <typename Scalar>
void DijkstraWithHeap(const MeshGraph& graph, int source, Scalar* dist,
                      DijkstraWorkspace<Scalar>* ws);

// The vertices within graph distance `radius` of `source` and their distances, in order of
// increasing distance. Cost is proportional to the size of the ball, not to #V.
void DijkstraBall(const MeshGraph& graph, int source, double radius,
                  std::vector<std::pair<int, double>>* ball, DijkstraWorkspace<double>* ws);

// Incremental form used by farthest point sampling: lowers min_dist[v] to the graph distance
// from `source` wherever that is smaller, visiting only vertices whose value decreases.
// Returns the number of values lowered (a vertex lowered twice counts twice).
int DijkstraUpdateMin(const MeshGraph& graph, int source, std::vector<double>* min_dist,
                      DijkstraWorkspace<double>* ws);

// Multi-source shortest paths from `seeds` (vertex ids): for every vertex the index into seeds
// of the seed nearest along the edges, -1 where no seed is reachable (another component). A
// vertex listed as several seeds belongs to the first. Ties go to the seed whose path reaches
// the vertex first in (distance, vertex id) order. Throws InvalidInputError for a seed id out
// of range.
std::vector<int> NearestSeeds(const MeshGraph& graph, const std::vector<int>& seeds);

}  // namespace symembed

// Edge-graph distance rows (core/mesh_graph.h) from vertices of surfaces, each computed once and
// kept for later calls: a partial pair's matching asks for the rows of the same vertices of a
// shape many times (the whole's samples in every pair it is in, the landmarks' images that
// recur across hypotheses and refinement rounds).
//
// A surface is named by a 64-bit key the caller derives from its content (e.g. a hash of its
// vertices and faces), so two calls on one shape share its rows and two different shapes never
// do. Rows are in the graph's units; a row from the cache equals the row EdgeGraphDistances
// computes (Dijkstra from one source is deterministic). Rows beyond `max_bytes` are dropped,
// least recently used first. Thread-safe: rows missing in two threads at once are computed in
// both, and the result is the same. Throws what EdgeGraphDistances throws.
#pragma once

#include <cstddef>
#include <cstdint>
#include <list>
#include <mutex>
#include <unordered_map>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "core/mesh_graph.h"

namespace symembed {

class EdgeDistanceCache {
 public:
  explicit EdgeDistanceCache(size_t max_bytes) : max_bytes_(max_bytes) {}
  EdgeDistanceCache(const EdgeDistanceCache&) = delete;
  EdgeDistanceCache& operator=(const EdgeDistanceCache&) = delete;

  // #sources x #V distances on `graph` (the surface of `surface_key`), from the rows kept and
  // one thread's Dijkstra for the others.
  Eigen::MatrixXd Rows(uint64_t surface_key, const MeshGraph& graph,
                       const std::vector<int>& sources);

  size_t Bytes() const;

 private:
  struct RowKey {
    uint64_t surface;
    int vertex;
    bool operator==(const RowKey& o) const { return surface == o.surface && vertex == o.vertex; }
  };
  struct RowKeyHash {
    size_t operator()(const RowKey& k) const {
      return static_cast<size_t>(k.surface ^ (static_cast<uint64_t>(k.vertex) * 0x9e3779b97f4a7c15ULL));
    }
  };
  using Recency = std::list<RowKey>;  // most recently used first
  struct Row {
    Eigen::VectorXd values;
    Recency::iterator recency;
  };

  size_t max_bytes_;
  mutable std::mutex mutex_;
  std::unordered_map<RowKey, Row, RowKeyHash> rows_;
  Recency recency_;
  size_t bytes_ = 0;
};

}  // namespace symembed

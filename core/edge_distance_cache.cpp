#include "core/edge_distance_cache.h"

namespace symembed {

Eigen::MatrixXd EdgeDistanceCache::Rows(uint64_t surface_key, const MeshGraph& graph,
                                        const std::vector<int>& sources) {
  const int n = graph.NumVertices();
  Eigen::MatrixXd out(sources.size(), n);
  std::vector<int> missing, missing_at;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (size_t i = 0; i < sources.size(); ++i) {
      auto it = rows_.find({surface_key, sources[i]});
      if (it == rows_.end() || it->second.values.size() != n) {
        missing.push_back(sources[i]);
        missing_at.push_back(static_cast<int>(i));
        continue;
      }
      out.row(i) = it->second.values.transpose();
      recency_.splice(recency_.begin(), recency_, it->second.recency);
    }
  }
  if (missing.empty()) return out;
  // The lock is not held while the rows are computed: other threads go on with other pairs.
  const Eigen::MatrixXd computed = EdgeGraphDistances(graph, missing, 1);
  std::lock_guard<std::mutex> lock(mutex_);
  const size_t row_bytes = static_cast<size_t>(n) * sizeof(double);
  for (size_t m = 0; m < missing.size(); ++m) {
    out.row(missing_at[m]) = computed.row(m);
    if (row_bytes > max_bytes_) continue;
    const RowKey key{surface_key, missing[m]};
    auto it = rows_.find(key);
    if (it != rows_.end() && it->second.values.size() == n) {
      recency_.splice(recency_.begin(), recency_, it->second.recency);
      continue;
    }
    if (it != rows_.end()) {
      bytes_ -= static_cast<size_t>(it->second.values.size()) * sizeof(double);
      recency_.erase(it->second.recency);
      rows_.erase(it);
    }
    while (bytes_ + row_bytes > max_bytes_ && !recency_.empty()) {
      auto last = rows_.find(recency_.back());
      bytes_ -= static_cast<size_t>(last->second.values.size()) * sizeof(double);
      rows_.erase(last);
      recency_.pop_back();
    }
    recency_.push_front(key);
    rows_.emplace(key, Row{computed.row(m).transpose(), recency_.begin()});
    bytes_ += row_bytes;
  }
  return out;
}

size_t EdgeDistanceCache::Bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return bytes_;
}

}  // namespace symembed

#include "core/mesh_graph.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <queue>
#include <string>

#include "core/errors.h"
#include "core/parallel.h"

namespace symembed {

MeshGraph BuildMeshGraph(const Surface& s) {
  const int n = s.NumVertices();
  // Each directed edge (both directions of every face edge) in its first vertex's list: counted,
  // placed, then each list sorted and deduplicated, which orders the edges by (from, to) as one
  // sort of all of them would, in time linear in the faces.
  std::vector<int> start(n + 1, 0);
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      SYMEMBED_CHECK(a >= 0 && a < n && b >= 0 && b < n, "face " << f << " has a bad vertex id");
      if (a == b) continue;
      ++start[a + 1];
      ++start[b + 1];
    }
  }
  for (int v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<int> to(start[n]);
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      if (a == b) continue;
      to[fill[a]++] = b;
      to[fill[b]++] = a;
    }
  }
  MeshGraph g;
  g.offsets.assign(n + 1, 0);
  g.neighbors.reserve(to.size() / 2 + 1);
  for (int v = 0; v < n; ++v) {
    const auto first = to.begin() + start[v], last = to.begin() + start[v + 1];
    std::sort(first, last);
    g.neighbors.insert(g.neighbors.end(), first, std::unique(first, last));
    g.offsets[v + 1] = static_cast<int>(g.neighbors.size());
  }
  g.lengths.resize(g.neighbors.size());
  for (int v = 0; v < n; ++v) {
    for (int e = g.offsets[v]; e < g.offsets[v + 1]; ++e) {
      g.lengths[e] = (s.V.row(v) - s.V.row(g.neighbors[e])).norm();
    }
  }
  if (!g.lengths.empty()) {
    const auto [lo, hi] = std::minmax_element(g.lengths.begin(), g.lengths.end());
    g.min_length = *lo;
    g.max_length = *hi;
  }
  return g;
}

namespace {

// A binary min-heap on (distance, vertex) with lazy deletion: stale entries are skipped when
// popped. Cheaper in practice than an indexed heap with decrease-key on mesh graphs, where
// each vertex is pushed only a few times.
template <typename Scalar>
struct MinHeap {
  std::vector<std::pair<Scalar, int>>& items;
  // A function object, not a function pointer, so that the heap operations inline it.
  struct Greater {
    bool operator()(const std::pair<Scalar, int>& a, const std::pair<Scalar, int>& b) const {
      return a.first > b.first;
    }
  };
  void Push(Scalar d, int v) {
    items.emplace_back(d, v);
    std::push_heap(items.begin(), items.end(), Greater());
  }
  std::pair<Scalar, int> Pop() {
    std::pop_heap(items.begin(), items.end(), Greater());
    auto top = items.back();
    items.pop_back();
    return top;
  }
  bool Empty() const { return items.empty(); }
};

// A graph's arrays as plain pointers. A loop that holds them (by value) keeps them in registers;
// through the vectors, each store the compiler cannot tell apart (a char flag may alias
// anything) would make it load their data pointers again.
struct GraphArrays {
  GraphArrays(const MeshGraph& g)  // NOLINT: implicit, so LowerNeighbours takes a MeshGraph too
      : offsets(g.offsets.data()), neighbors(g.neighbors.data()), lengths(g.lengths.data()) {}
  const int* offsets;
  const int* neighbors;
  const double* lengths;
};

// Relaxes the edges out of v, settled at distance d: wherever d + length is below dist[w], lowers
// dist[w] to it and calls on_lower(w, the new value).
template <typename Scalar, typename OnLower>
inline void LowerNeighbours(GraphArrays g, int v, Scalar d, Scalar* dist, OnLower on_lower) {
  const int end = g.offsets[v + 1];
  for (int k = g.offsets[v]; k < end; ++k) {
    const int w = g.neighbors[k];
    const Scalar nd = d + static_cast<Scalar>(g.lengths[k]);
    if (nd < dist[w]) {
      dist[w] = nd;
      on_lower(w, nd);
    }
  }
}

}  // namespace

template <typename Scalar>
void DijkstraWithHeap(const MeshGraph& g, int source, Scalar* dist, DijkstraWorkspace<Scalar>* ws) {
  const int n = g.NumVertices();
  SYMEMBED_CHECK(source >= 0 && source < n, "source " << source << " out of range");
  std::fill(dist, dist + n, std::numeric_limits<Scalar>::infinity());
  ws->heap.clear();
  MinHeap<Scalar> heap{ws->heap};
  dist[source] = 0;
  heap.Push(0, source);
  while (!heap.Empty()) {
    const auto [d, v] = heap.Pop();
    if (d > dist[v]) continue;  // stale entry
    LowerNeighbours(g, v, d, dist, [&](int w, Scalar nd) { heap.Push(nd, w); });
  }
}

template <typename Scalar>
void Dijkstra(const MeshGraph& g, int source, Scalar* dist, DijkstraWorkspace<Scalar>* ws) {
  const int n = g.NumVertices();
  SYMEMBED_CHECK(source >= 0 && source < n, "source " << source << " out of range");
  // Buckets of width half the shortest edge: a relaxation from bucket i (a value at least
  // i * width, up to rounding) adds at least two widths, so it lands in bucket i + 2 or later
  // even after rounding, and nothing can lower a value in the lowest non-empty bucket.
  constexpr double kMaxSpread = 1000.0;
  const Scalar width = static_cast<Scalar>(0.5 * g.min_length);
  if (!(g.min_length > 0.0) || g.max_length > kMaxSpread * g.min_length || !(width > 0)) {
    DijkstraWithHeap(g, source, dist, ws);
    return;
  }
  const Scalar inv_width = Scalar(1) / width;
  // Values in the queue lie below the current bucket's start plus the longest edge plus a width
  // (a relaxation from the current bucket), so this many buckets never wrap onto a live one.
  // A power of two, so that a bucket's slot is a mask, not a division.
  const long long needed = static_cast<long long>(std::ceil(g.max_length / (0.5 * g.min_length))) + 4;
  long long num_buckets = 1;
  while (num_buckets < needed) num_buckets *= 2;
  const long long mask = num_buckets - 1;
  auto& buckets = ws->buckets;
  if (static_cast<long long>(buckets.size()) < num_buckets) buckets.resize(num_buckets);
  for (auto& b : buckets) b.clear();
  ws->settled.assign(n, 0);
  std::fill(dist, dist + n, std::numeric_limits<Scalar>::infinity());
  auto bucket_of = [&](Scalar d) {
    return static_cast<long long>(d * inv_width);
  };
  dist[source] = 0;
  buckets[0].push_back(source);
  long long queued = 1;  // entries in the buckets, stale ones included
  // Plain pointers, held in registers (GraphArrays).
  const GraphArrays arrays(g);
  char* settled = ws->settled.data();
  std::vector<int>* slots = buckets.data();
  for (long long current = 0; queued > 0; ++current) {
    std::vector<int>& bucket = slots[current & mask];
    // By index: nothing lands in the current bucket (see above), but an iterator would not
    // survive it.
    for (size_t i = 0; i < bucket.size(); ++i) {
      const int v = bucket[i];
      // A stale entry: v was settled already, or lowered into an earlier bucket and settled there.
      if (settled[v]) continue;
      settled[v] = 1;
      LowerNeighbours(arrays, v, dist[v], dist, [&](int w, Scalar nd) {
        slots[bucket_of(nd) & mask].push_back(w);
        ++queued;
      });
    }
    queued -= static_cast<long long>(bucket.size());
    bucket.clear();
  }
}

template void Dijkstra<double>(const MeshGraph&, int, double*, DijkstraWorkspace<double>*);
template void Dijkstra<float>(const MeshGraph&, int, float*, DijkstraWorkspace<float>*);
template void DijkstraWithHeap<double>(const MeshGraph&, int, double*, DijkstraWorkspace<double>*);
template void DijkstraWithHeap<float>(const MeshGraph&, int, float*, DijkstraWorkspace<float>*);

void DijkstraBall(const MeshGraph& g, int source, double radius,
                  std::vector<std::pair<int, double>>* ball, DijkstraWorkspace<double>* ws) {
  const int n = g.NumVertices();
  SYMEMBED_CHECK(source >= 0 && source < n, "source " << source << " out of range");
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double>& dist = ws->ball_dist;
  if (static_cast<int>(dist.size()) != n) dist.assign(n, kInf);
  ball->clear();
  ws->heap.clear();
  MinHeap<double> heap{ws->heap};
  // Every vertex given a finite value is remembered so that it can be reset afterwards.
  std::vector<int> touched{source};
  dist[source] = 0.0;
  heap.Push(0.0, source);
  while (!heap.Empty()) {
    const auto [d, v] = heap.Pop();
    if (d > dist[v]) continue;
    ball->emplace_back(v, d);
    for (int k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
      const int w = g.neighbors[k];
      const double nd = d + g.lengths[k];
      if (nd <= radius && nd < dist[w]) {
        if (dist[w] == kInf) touched.push_back(w);
        dist[w] = nd;
        heap.Push(nd, w);
      }
    }
  }
  for (int v : touched) dist[v] = kInf;
}

int DijkstraUpdateMin(const MeshGraph& g, int source, std::vector<double>* min_dist,
                      DijkstraWorkspace<double>* ws) {
  std::vector<double>& dist = *min_dist;
  SYMEMBED_CHECK(static_cast<int>(dist.size()) == g.NumVertices(), "min_dist has the wrong size");
  ws->heap.clear();
  MinHeap<double> heap{ws->heap};
  int changed = 0;
  if (dist[source] > 0.0) {
    dist[source] = 0.0;
    ++changed;
  }
  heap.Push(0.0, source);
  // Every vertex whose distance to `source` is below its current value is reached through
  // vertices that are also improved (a shortest path's prefix is shortest), so the search can
  // stop expanding wherever it does not improve.
  while (!heap.Empty()) {
    const auto [d, v] = heap.Pop();
    if (d > dist[v]) continue;
    LowerNeighbours(g, v, d, dist.data(), [&](int w, double nd) {
      ++changed;
      heap.Push(nd, w);
    });
  }
  return changed;
}

std::vector<int> NearestSeeds(const MeshGraph& g, const std::vector<int>& seeds) {
  const int n = g.NumVertices();
  std::vector<double> dist(n, std::numeric_limits<double>::infinity());
  std::vector<int> label(n, -1);
  // Ordered by (distance, vertex) rather than by distance alone, so that ties between seeds do
  // not depend on the heap's layout.
  using Entry = std::pair<double, int>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> queue;
  for (int k = 0; k < static_cast<int>(seeds.size()); ++k) {
    const int v = seeds[k];
    if (v < 0 || v >= n) {
      throw InvalidInputError("seed " + std::to_string(k) + " is vertex " + std::to_string(v) +
                              " of a graph with " + std::to_string(n) + " vertices");
    }
    if (label[v] >= 0) continue;
    dist[v] = 0.0;
    label[v] = k;
  }
  for (int v = 0; v < n; ++v) {
    if (label[v] >= 0) queue.push({0.0, v});
  }
  while (!queue.empty()) {
    const auto [d, v] = queue.top();
    queue.pop();
    if (d > dist[v]) continue;
    LowerNeighbours(g, v, d, dist.data(), [&](int w, double nd) {
      label[w] = label[v];
      queue.push({nd, w});
    });
  }
  return label;
}

Eigen::MatrixXd EdgeGraphDistances(const Surface& surface, const std::vector<int>& sources,
                                   int threads) {
  return EdgeGraphDistances(BuildMeshGraph(surface), sources, threads);
}

Eigen::MatrixXd EdgeGraphDistances(const MeshGraph& graph, const std::vector<int>& sources,
                                   int threads) {
  return ParallelRows(sources, graph.NumVertices(), threads, [&](int i, double* out) {
    thread_local DijkstraWorkspace<double> ws;
    Dijkstra<double>(graph, sources[i], out, &ws);
  });
}

}  // namespace symembed

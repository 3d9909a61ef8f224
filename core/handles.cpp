#include "core/handles.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <limits>
#include <numeric>
#include <queue>
#include <unordered_map>

#include "core/mesh_graph.h"

namespace symembed {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

uint64_t Key(int a, int b) {
  return (static_cast<uint64_t>(static_cast<uint32_t>(a)) << 32) | static_cast<uint32_t>(b);
}

// Connectivity of a triangle mesh: directed edges to their face, faces of each vertex, the
// edge graph, boundary vertices and connected components.
struct Topology {
  int nv = 0;
  std::unordered_map<uint64_t, int> directed;   // (a, b) -> the face that runs a -> b
  std::vector<std::vector<int>> faces_of;       // vertex -> faces
  std::vector<char> boundary;                   // vertex on an edge with one face
  std::vector<int> component;                   // vertex -> component (-1: unreferenced)
  std::vector<int> hole;                        // boundary vertex -> its boundary loop, else -1
  std::vector<std::vector<int>> hole_vertices;  // boundary loop -> its vertices
  int components = 0;
  int genus = 0;
  bool manifold = true;  // every directed edge once, every undirected edge in <= 2 faces
  MeshGraph graph;
};

// with_graph: also the edge graph (the search needs it; the genus does not).
Topology BuildTopology(const Surface& s, bool with_graph = true) {
  Topology t;
  t.nv = s.NumVertices();
  t.faces_of.assign(t.nv, {});
  t.boundary.assign(t.nv, 0);
  t.component.assign(t.nv, -1);
  std::unordered_map<uint64_t, int> undirected;
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      if (!t.directed.emplace(Key(a, b), f).second) t.manifold = false;
      if (++undirected[Key(std::min(a, b), std::max(a, b))] > 2) t.manifold = false;
      t.faces_of[a].push_back(f);
    }
  }
  // Components through shared vertices, boundary edges and their loops.
  std::vector<int> parent(t.nv);
  std::iota(parent.begin(), parent.end(), 0);
  std::function<int(int)> find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (int f = 0; f < s.NumFaces(); ++f) {
    for (int k = 1; k < 3; ++k) parent[find(s.F(f, k))] = find(s.F(f, 0));
  }
  std::vector<int> loop_parent(t.nv);
  std::iota(loop_parent.begin(), loop_parent.end(), 0);
  auto find_loop = [&](int v) {
    while (loop_parent[v] != v) v = loop_parent[v] = loop_parent[loop_parent[v]];
    return v;
  };
  for (const auto& [key, count] : undirected) {
    if (count != 1) continue;
    const int a = static_cast<int>(key >> 32), b = static_cast<int>(key & 0xffffffffu);
    t.boundary[a] = t.boundary[b] = 1;
    loop_parent[find_loop(a)] = find_loop(b);
  }
  std::unordered_map<int, int> label;
  long long referenced = 0, loops = 0;
  for (int v = 0; v < t.nv; ++v) {
    if (t.faces_of[v].empty()) continue;
    ++referenced;
    auto [it, inserted] = label.emplace(find(v), static_cast<int>(label.size()));
    t.component[v] = it->second;
    if (t.boundary[v] && find_loop(v) == v) ++loops;
  }
  t.hole.assign(t.nv, -1);
  std::unordered_map<int, int> hole_label;
  for (int v = 0; v < t.nv; ++v) {
    if (!t.boundary[v]) continue;
    auto [it, inserted] = hole_label.emplace(find_loop(v), static_cast<int>(hole_label.size()));
    if (inserted) t.hole_vertices.emplace_back();
    t.hole[v] = it->second;
    t.hole_vertices[it->second].push_back(v);
  }
  t.components = static_cast<int>(label.size());
  const long long chi = referenced - static_cast<long long>(undirected.size()) + s.NumFaces();
  t.genus = t.manifold ? static_cast<int>((2 * t.components - chi - loops) / 2) : -1;
  if (with_graph) t.graph = BuildMeshGraph(s);
  return t;
}

// The neighbours of v in order around it, one path per fan of faces around v: a cycle (closed)
// for an interior vertex, a path from one boundary edge to the other for each fan of a boundary
// vertex (a pinched vertex, as a cut can leave, has several).
struct LinkPath {
  std::vector<int> vertices;
  bool closed = false;
};

std::vector<LinkPath> Link(const Surface& s, const Topology& t, int v) {
  std::unordered_map<int, int> next;  // u -> w for each face (v, u, w)
  std::unordered_map<int, int> has_previous;
  for (int f : t.faces_of[v]) {
    int k = 0;
    while (s.F(f, k) != v) ++k;
    next[s.F(f, (k + 1) % 3)] = s.F(f, (k + 2) % 3);
    ++has_previous[s.F(f, (k + 2) % 3)];
  }
  std::vector<LinkPath> paths;
  std::unordered_map<int, char> used;
  auto walk = [&](int start, bool closed) {
    LinkPath path;
    path.closed = closed;
    for (int u = start;;) {
      path.vertices.push_back(u);
      used[u] = 1;
      auto it = next.find(u);
      if (it == next.end() || it->second == start || used.count(it->second)) break;
      u = it->second;
    }
    paths.push_back(std::move(path));
  };
  for (const auto& [u, w] : next) {
    if (!has_previous.count(u)) walk(u, false);  // the start of an open fan
  }
  for (const auto& [u, w] : next) {
    if (!used.count(u)) walk(u, true);
  }
  return paths;
}

// Components of the vertices of `component` not in `blocked`, along the graph's edges, with
// each boundary loop counted as one more vertex joined to its own boundary vertices (the hole
// filled in): a cycle around a hole then separates the hole from the rest, as on a sphere.
int CountComponents(const Topology& t, int component, const std::vector<char>& blocked) {
  const int holes = static_cast<int>(t.hole_vertices.size());
  std::vector<char> seen(t.nv + holes, 0);
  std::vector<int> stack;
  int count = 0;
  auto visit = [&](int node) {
    if (seen[node]) return;
    if (node < t.nv && (blocked[node] || t.component[node] != component)) return;
    if (node >= t.nv && t.component[t.hole_vertices[node - t.nv][0]] != component) return;
    seen[node] = 1;
    stack.push_back(node);
  };
  for (int start = 0; start < t.nv + holes; ++start) {
    const size_t before = stack.size();
    visit(start);
    if (stack.size() == before) continue;
    ++count;
    while (!stack.empty()) {
      const int u = stack.back();
      stack.pop_back();
      if (u >= t.nv) {
        for (int w : t.hole_vertices[u - t.nv]) visit(w);
        continue;
      }
      if (t.hole[u] >= 0) visit(t.nv + t.hole[u]);
      for (int i = t.graph.offsets[u]; i < t.graph.offsets[u + 1]; ++i) visit(t.graph.neighbors[i]);
    }
  }
  return count;
}

struct Event {
  double radius = kInf;
  int seed = -1, meet = -1;
  std::vector<int> pred;  // the seed's shortest-path tree at the event
  std::vector<char> in_ball;
};

// Grows the ball of `seed` until its front closes a cycle that splits off no component of the
// unreached vertices and holes (a handle's) at a vertex not `banned`, or past `limit`.
// Per-thread state of GrowBall, reset through the vertices it touched.
struct BallWorkspace {
  std::vector<double> dist;
  std::vector<int> pred;
  std::vector<char> in_ball;
  std::vector<int> touched;
  explicit BallWorkspace(int nv) : dist(nv, kInf), pred(nv, -1), in_ball(nv, 0) {}
  void Reset() {
    for (int v : touched) {
      dist[v] = kInf;
      pred[v] = -1;
      in_ball[v] = 0;
    }
    touched.clear();
  }
};

Event GrowBall(const Surface& s, const Topology& t, int seed, double limit,
               const std::vector<char>& banned, BallWorkspace* ws) {
  Event e;
  ws->Reset();
  std::vector<double>& dist = ws->dist;
  std::vector<int>& pred = ws->pred;
  std::vector<char>& in_ball = ws->in_ball;
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> heap;
  dist[seed] = 0.0;
  ws->touched.push_back(seed);
  heap.push({0.0, seed});
  int outside_components = 1;
  const int component = t.component[seed];
  while (!heap.empty()) {
    const auto [d, x] = heap.top();
    heap.pop();
    if (d > dist[x] || in_ball[x]) continue;
    if (d >= limit) break;
    int edges = 0, faces = 0;
    bool island = !t.boundary[x];  // a boundary vertex stays joined to its hole
    for (int i = t.graph.offsets[x]; i < t.graph.offsets[x + 1]; ++i) {
      if (in_ball[t.graph.neighbors[i]]) {
        ++edges;
      } else {
        island = false;
      }
    }
    for (int f : t.faces_of[x]) {
      int others = 0;
      for (int k = 0; k < 3; ++k) others += s.F(f, k) != x && in_ball[s.F(f, k)];
      faces += others == 2;
    }
    in_ball[x] = 1;
    if (island) --outside_components;
    const int new_cycles = edges - faces - 1;  // the drop of the ball's Euler characteristic
    if (new_cycles > 0) {
      const int now = CountComponents(t, component, in_ball);
      const int separating = now - outside_components;
      outside_components = now;
      if (new_cycles > separating && !banned[x]) {
        e.radius = d;
        e.seed = seed;
        e.meet = x;
        e.pred = pred;
        e.in_ball = in_ball;
        return e;
      }
    }
    for (int i = t.graph.offsets[x]; i < t.graph.offsets[x + 1]; ++i) {
      const int w = t.graph.neighbors[i];
      const double dw = d + t.graph.lengths[i];
      if (!in_ball[w] && dw < dist[w]) {
        if (dist[w] == kInf) ws->touched.push_back(w);
        dist[w] = dw;
        pred[w] = x;
        heap.push({dw, w});
      }
    }
  }
  return e;
}

// The loop a -> (tree) -> common ancestor -> (tree) -> b -> meet -> a.
std::vector<int> TreeLoop(const std::vector<int>& pred, int meet, int a, int b) {
  std::vector<int> up_a, up_b;
  for (int v = a; v >= 0; v = pred[v]) up_a.push_back(v);
  std::unordered_map<int, size_t> index_a;
  for (size_t i = 0; i < up_a.size(); ++i) index_a[up_a[i]] = i;
  int v = b;
  while (v >= 0 && !index_a.count(v)) {
    up_b.push_back(v);
    v = pred[v];
  }
  if (v < 0) return {};
  std::vector<int> loop = {meet};
  loop.insert(loop.end(), up_a.begin(), up_a.begin() + static_cast<long>(index_a[v]) + 1);
  loop.insert(loop.end(), up_b.rbegin(), up_b.rend());
  return loop;
}

// The faces on the left of the closed loop: at each loop vertex, its fan from the outgoing loop
// edge round to the incoming one, walked from both ends when a hole interrupts it (where the
// loop runs along a hole, the hole is its left side there and nothing is added).
std::vector<int> LeftStrip(const Surface& s, const Topology& t, const std::vector<int>& loop) {
  std::vector<int> strip;
  const size_t n = loop.size();
  auto third = [&](int f, int g, int offset) {
    int k = 0;
    while (s.F(f, k) != g) ++k;
    return s.F(f, (k + offset) % 3);
  };
  for (size_t i = 0; i < n; ++i) {
    const int p = loop[(i + n - 1) % n], g = loop[i], q = loop[(i + 1) % n];
    const size_t limit = t.faces_of[g].size();
    // Forwards from the face on the left of g -> q: (g, u, w), then the face of g -> w.
    bool reached = false;
    int u = q;
    for (size_t steps = 0; steps <= limit; ++steps) {
      auto it = t.directed.find(Key(g, u));
      if (it == t.directed.end()) break;
      strip.push_back(it->second);
      u = third(it->second, g, 2);
      if (u == p) {
        reached = true;
        break;
      }
    }
    if (reached) continue;
    // A hole interrupts the fan: backwards from the face on the left of p -> g, (g, w, p),
    // then the face of w -> g.
    u = p;
    for (size_t steps = 0; steps <= limit; ++steps) {
      auto it = t.directed.find(Key(u, g));
      if (it == t.directed.end()) break;
      strip.push_back(it->second);
      u = third(it->second, g, 1);
    }
  }
  std::sort(strip.begin(), strip.end());
  strip.erase(std::unique(strip.begin(), strip.end()), strip.end());
  return strip;
}

// The vertices that removing `faces` leaves without a face.
int IsolatedBy(const Surface& s, const Topology& t, const std::vector<int>& faces) {
  std::vector<int> left(t.nv, 0);
  for (int v = 0; v < t.nv; ++v) left[v] = static_cast<int>(t.faces_of[v].size());
  int isolated = 0;
  for (int f : faces) {
    for (int k = 0; k < 3; ++k) isolated += --left[s.F(f, k)] == 0;
  }
  return isolated;
}

// Seeds: `count` spread over every component by farthest-point sampling along the edges, then
// every other vertex, so that a handle's own vertices seed a ball (its shortest loop is found
// at about half its length) while the spread seeds bound the radius early.
std::vector<int> Seeds(const Topology& t, int count) {
  std::vector<double> nearest(t.nv, kInf);
  DijkstraWorkspace<double> workspace;
  std::vector<int> seeds;
  for (int i = 0; i < count; ++i) {
    int best = -1;
    for (int v = 0; v < t.nv; ++v) {
      if (t.component[v] < 0) continue;
      if (best < 0 || nearest[v] > nearest[best]) best = v;
    }
    if (best < 0 || nearest[best] == 0.0) break;
    seeds.push_back(best);
    nearest[best] = 0.0;
    DijkstraUpdateMin(t.graph, best, &nearest, &workspace);
  }
  std::vector<char> chosen(t.nv, 0);
  for (int v : seeds) chosen[v] = 1;
  for (int v = 0; v < t.nv; ++v) {
    if (!chosen[v] && t.component[v] >= 0) seeds.push_back(v);
  }
  return seeds;
}

double LoopLength(const Surface& s, const std::vector<int>& loop) {
  double length = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) {
    length += (s.V.row(loop[i]) - s.V.row(loop[(i + 1) % loop.size()])).norm();
  }
  return length;
}

// A cut of the handle an event found: the loop, the strip of faces along it, and the surface
// and topology after the strip is removed. strip is empty when no strip severs the handle.
struct CutPlan {
  std::vector<int> loop;
  std::vector<int> strip;
  Surface cut;
  Topology after;
  int isolated = 0;     // vertices the strip leaves without a face
  double detour = 0.0;  // median distance, after the cut, between the vertices it separates
};

constexpr size_t kCandidates = 6;

CutPlan PlanCut(const Surface& s, const Topology& t, const Event& event,
                const Eigen::VectorXd& face_areas) {
  CutPlan plan;
  // The meeting vertex's neighbours in the ball form two or more arcs around it; the loop
  // through one vertex of each of two arcs is the handle's when it does not separate.
  std::vector<std::vector<int>> arcs;
  for (const LinkPath& path : Link(s, t, event.meet)) {
    const std::vector<int>& link = path.vertices;
    const size_t first = arcs.size();
    for (size_t i = 0; i < link.size(); ++i) {
      if (!event.in_ball[link[i]]) continue;
      if (i == 0 || !event.in_ball[link[i - 1]]) arcs.push_back({});
      arcs.back().push_back(link[i]);
    }
    if (path.closed && arcs.size() > first + 1 && event.in_ball[link.front()] &&
        event.in_ball[link.back()]) {
      arcs[first].insert(arcs[first].end(), arcs.back().begin(), arcs.back().end());
      arcs.pop_back();
    }
  }
  for (size_t i = 0; i < arcs.size() && plan.loop.empty(); ++i) {
    for (size_t j = i + 1; j < arcs.size() && plan.loop.empty(); ++j) {
      std::vector<int> candidate =
          TreeLoop(event.pred, event.meet, arcs[i].front(), arcs[j].front());
      if (candidate.size() < 3) continue;
      std::vector<char> on_loop(t.nv, 0);
      for (int v : candidate) on_loop[v] = 1;
      if (CountComponents(t, t.component[event.meet], on_loop) == 1) {
        plan.loop = std::move(candidate);
      }
    }
  }
  if (plan.loop.empty()) return plan;
  // Of the strips on the two sides of the loop that sever the handle (the genus drops, the
  // surface stays in one piece; where the loop runs along an earlier cut, only the side away
  // from the hole can), the one that leaves fewer vertices without a face, then the one of
  // less area (a thin bridge goes rather than the body around its end).
  std::vector<int> loop = plan.loop;
  std::pair<int, double> best_cost(std::numeric_limits<int>::max(), kInf);
  for (int side = 0; side < 2; ++side) {
    if (side == 1) std::reverse(loop.begin(), loop.end());
    std::vector<int> candidate = LeftStrip(s, t, loop);
    if (candidate.empty()) continue;
    double area = 0.0;
    for (int f : candidate) area += face_areas(f);
    const std::pair<int, double> cost(IsolatedBy(s, t, candidate), area);
    if (!(cost < best_cost)) continue;
    std::vector<char> removed(s.NumFaces(), 0);
    for (int f : candidate) removed[f] = 1;
    Surface cut = s;
    cut.F.resize(s.NumFaces() - static_cast<int>(candidate.size()), 3);
    for (int f = 0, row = 0; f < s.NumFaces(); ++f) {
      if (!removed[f]) cut.F.row(row++) = s.F.row(f);
    }
    Topology after = BuildTopology(cut);
    if (after.components != t.components || after.genus >= t.genus) continue;
    best_cost = cost;
    plan.strip = std::move(candidate);
    plan.cut = std::move(cut);
    plan.after = std::move(after);
    plan.isolated = cost.first;
  }
  if (plan.strip.empty()) return plan;
  // How far apart the cut puts the vertices of each removed face: loop vertex to strip vertex.
  std::vector<char> on_loop(t.nv, 0);
  for (int v : plan.loop) on_loop[v] = 1;
  std::vector<double> dist(t.nv);
  DijkstraWorkspace<double> workspace;
  std::vector<double> separations;
  std::unordered_map<int, std::vector<int>> across;  // loop vertex -> strip vertices
  for (int f : plan.strip) {
    for (int k = 0; k < 3; ++k) {
      const int g = s.F(f, k);
      if (!on_loop[g]) continue;
      for (int m = 0; m < 3; ++m) {
        const int l = s.F(f, m);
        if (!on_loop[l] && !plan.after.faces_of[l].empty()) across[g].push_back(l);
      }
    }
  }
  for (const auto& [g, others] : across) {
    if (plan.after.faces_of[g].empty()) continue;
    Dijkstra(plan.after.graph, g, dist.data(), &workspace);
    for (int l : others) separations.push_back(dist[l]);
  }
  if (!separations.empty()) {
    std::nth_element(separations.begin(), separations.begin() + separations.size() / 2,
                     separations.end());
    plan.detour = separations[separations.size() / 2];
  }
  return plan;
}

// Closes the boundary loops of `after` whose edges all had two faces in `before` (the loops a
// removal of faces opened) with faces between each loop's vertices, appended to *F. The
// polygon is triangulated as a zigzag from both ends of the loop, which keeps the triangles
// less thin than a fan from one vertex. Returns the loops closed.
int CapOpenedLoops(const Eigen::MatrixX3i& before, Eigen::MatrixX3i* F) {
  auto key = [](int a, int b) {
    return (static_cast<uint64_t>(static_cast<uint32_t>(std::min(a, b))) << 32) |
           static_cast<uint32_t>(std::max(a, b));
  };
  std::unordered_map<uint64_t, int> faces_before, faces_after;
  for (int f = 0; f < before.rows(); ++f) {
    for (int k = 0; k < 3; ++k) ++faces_before[key(before(f, k), before(f, (k + 1) % 3))];
  }
  for (int f = 0; f < F->rows(); ++f) {
    for (int k = 0; k < 3; ++k) ++faces_after[key((*F)(f, k), (*F)(f, (k + 1) % 3))];
  }
  // Boundary half-edges u -> v of the faces kept on an edge that had two faces before.
  std::unordered_map<int, std::vector<int>> next;
  for (int f = 0; f < F->rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int u = (*F)(f, k), v = (*F)(f, (k + 1) % 3);
      if (faces_after[key(u, v)] == 1 && faces_before[key(u, v)] == 2) next[u].push_back(v);
    }
  }
  std::vector<std::array<int, 3>> added;
  std::unordered_map<int, char> used;
  std::vector<int> starts;
  for (const auto& [u, vs] : next) starts.push_back(u);
  std::sort(starts.begin(), starts.end());
  int capped = 0;
  for (int start : starts) {
    if (used[start]) continue;
    std::vector<int> loop = {start};
    bool simple = next[start].size() == 1;
    used[start] = 1;
    for (int v = next[start][0]; simple && v != start;) {
      auto it = next.find(v);
      if (it == next.end() || it->second.size() != 1 || used[v]) {
        simple = false;
        break;
      }
      used[v] = 1;
      loop.push_back(v);
      v = it->second[0];
    }
    if (!simple || loop.size() < 3) continue;
    // The closing polygon runs the loop backwards, so that each of its edges is the twin of
    // the kept face's half-edge on it.
    std::vector<int> p(loop.size());
    p[0] = loop[0];
    for (size_t i = 1; i < loop.size(); ++i) p[i] = loop[loop.size() - i];
    std::vector<std::array<int, 3>> faces;
    int a = 0, b = static_cast<int>(p.size()) - 1;
    for (bool front = true; b - a >= 2; front = !front) {
      if (front) {
        faces.push_back({p[a], p[a + 1], p[b]});
        ++a;
      } else {
        faces.push_back({p[a], p[b - 1], p[b]});
        --b;
      }
    }
    // The diagonals are new edges: one the surface has already would get a third face.
    std::unordered_map<uint64_t, char> on_loop;
    for (size_t i = 0; i < loop.size(); ++i) on_loop[key(loop[i], loop[(i + 1) % loop.size()])] = 1;
    bool clear = true;
    for (const auto& t : faces) {
      for (int k = 0; k < 3 && clear; ++k) {
        const uint64_t e = key(t[k], t[(k + 1) % 3]);
        clear = on_loop.count(e) > 0 || faces_after.count(e) == 0;
      }
    }
    if (!clear) continue;
    for (const auto& t : faces) added.push_back(t);
    ++capped;
  }
  const Eigen::Index kept = F->rows();
  F->conservativeResize(kept + static_cast<Eigen::Index>(added.size()), 3);
  for (size_t i = 0; i < added.size(); ++i) {
    F->row(kept + static_cast<Eigen::Index>(i)) << added[i][0], added[i][1], added[i][2];
  }
  return capped;
}

}  // namespace

int SurfaceGenus(const Surface& surface) { return BuildTopology(surface, false).genus; }

HandleCutResult CutHandles(const Surface& surface, const HandleCutOptions& options) {
  HandleCutResult r;
  r.F = surface.F;
  Surface s = surface;
  Topology t = BuildTopology(s, false);
  r.genus_before = r.genus_after = t.genus;
  if (!t.manifold) {
    r.skipped =
        "not an oriented manifold (an edge in more than two faces, or run twice in "
        "one direction)";
    return r;
  }
  if (t.genus <= 0) return r;
  t.graph = BuildMeshGraph(s);
  // The vertices of loops that could not be cut (no strip, or one that would split the surface
  // or not lower its genus): events meeting there are passed over, a few times per cut at most.
  std::vector<char> banned(t.nv, 0);
  int failures = 0;
  while (t.genus > 0 && r.cuts < options.max_cuts && failures <= 4 * options.max_cuts) {
    const Eigen::VectorXd face_areas = FaceAreas(s);
    // The kCandidates events of smallest radius (each seed's first), smallest first.
    std::vector<Event> events;
    BallWorkspace workspace(t.nv);
    for (int seed : Seeds(t, options.seeds)) {
      const double limit = events.size() < kCandidates ? kInf : events.back().radius;
      Event e = GrowBall(s, t, seed, limit, banned, &workspace);
      if (e.seed < 0) continue;
      auto at = std::upper_bound(events.begin(), events.end(), e.radius,
                                 [](double radius, const Event& x) { return radius < x.radius; });
      events.insert(at, std::move(e));
      if (events.size() > kCandidates) events.pop_back();
    }
    if (events.empty()) break;
    // Of the events' cuts that sever their handle, the one whose cut lengthens the distance
    // across it most: a loop around a bridge, not a loop through two bridges side by side,
    // which would slit both and leave them joining what they join.
    CutPlan chosen;
    for (const Event& e : events) {
      CutPlan plan = PlanCut(s, t, e, face_areas);
      if (plan.strip.empty()) continue;
      if (chosen.strip.empty() || plan.detour > chosen.detour) chosen = std::move(plan);
    }
    if (chosen.strip.empty()) {
      const CutPlan first = PlanCut(s, t, events.front(), face_areas);
      if (first.loop.empty()) banned[events.front().meet] = 1;
      for (int v : first.loop) banned[v] = 1;
      ++failures;
      continue;
    }
    r.longest_loop = std::max(r.longest_loop, LoopLength(s, chosen.loop));
    r.removed_faces += static_cast<int>(chosen.strip.size());
    r.removed_vertices += chosen.isolated;
    ++r.cuts;
    s.F = chosen.cut.F;
    t = std::move(chosen.after);
  }
  r.F = s.F;
  r.genus_after = t.genus;
  if (options.cap && r.cuts > 0) {
    const Eigen::Index kept = r.F.rows();
    r.capped_loops = CapOpenedLoops(surface.F, &r.F);
    r.cap_faces = static_cast<int>(r.F.rows() - kept);
  }
  return r;
}

}  // namespace symembed

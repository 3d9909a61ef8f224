#include "core/validation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "core/errors.h"

namespace symembed {
namespace {

// Union-find over 0..n-1 with path halving.
class DisjointSets {
 public:
  explicit DisjointSets(int n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }
  int Find(int x) {
    while (parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  void Union(int a, int b) { parent_[Find(a)] = Find(b); }

 private:
  std::vector<int> parent_;
};

// Union-find that also keeps the parity of each element relative to its root: used to decide
// whether faces can be given a consistent orientation (parity 1 = flipped relative to the root).
class ParitySets {
 public:
  explicit ParitySets(int n) : parent_(n), parity_(n, 0) {
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  // Root of x; *parity receives x's parity relative to it.
  int Find(int x, int* parity) {
    int p = 0;
    int r = x;
    while (parent_[r] != r) {
      p ^= parity_[r];
      r = parent_[r];
    }
    // Second pass: point every element on the path at the root with its own parity.
    int q = p;
    while (parent_[x] != x) {
      const int next = parent_[x], next_parity = q ^ parity_[x];
      parent_[x] = r;
      parity_[x] = q;
      x = next;
      q = next_parity;
    }
    *parity = p;
    return r;
  }
  // Requires parity(a) ^ parity(b) == relation; false when that contradicts earlier relations.
  bool Relate(int a, int b, int relation) {
    int pa, pb;
    const int ra = Find(a, &pa), rb = Find(b, &pb);
    if (ra == rb) return (pa ^ pb) == relation;
    parent_[ra] = rb;
    parity_[ra] = pa ^ pb ^ relation;
    return true;
  }

 private:
  std::vector<int> parent_;
  std::vector<int> parity_;
};

// Collects up to `max` example strings for an issue line.
class Examples {
 public:
  explicit Examples(int max) : max_(max) {}
  void Add(const std::string& s) {
    if (static_cast<int>(items_.size()) < max_) items_.push_back(s);
  }
  std::string Suffix(const std::string& label) const {
    if (items_.empty()) return "";
    std::string out = " (e.g. " + label;
    for (size_t i = 0; i < items_.size(); ++i) out += (i ? ", " : " ") + items_[i];
    return out + ")";
  }

 private:
  int max_;
  std::vector<std::string> items_;
};

struct HalfEdge {
  int lo, hi;    // undirected edge, lo < hi
  int face;      // face id
  int corner;    // the half-edge runs from corner to corner + 1 of the face
  bool forward;  // traversed lo -> hi
};

// Non-manifold ("bow-tie") vertices: around each vertex the two edges of a face that meet at a
// corner are joined, and a vertex whose incident edges fall into more than one group is
// non-manifold. Node 2e + side stands for edge e seen from its endpoint edges[e][side].
// proper: per face, whether it has valid, distinct ids; face_edge: the edge id of each face
// corner. Adds the vertices to *examples and returns their count.
int CountNonManifoldVertices(const Surface& s, const std::vector<char>& proper,
                             const std::vector<int>& face_edge,
                             const std::vector<std::array<int, 2>>& edges, Examples* examples) {
  const int num_edges = static_cast<int>(edges.size());
  DisjointSets fans(2 * num_edges);
  auto node = [&](int e, int v) { return 2 * e + (edges[e][0] == v ? 0 : 1); };
  for (int f = 0; f < s.NumFaces(); ++f) {
    if (!proper[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const int v = s.F(f, k);
      fans.Union(node(face_edge[3 * f + k], v), node(face_edge[3 * f + (k + 2) % 3], v));
    }
  }
  std::vector<int> fan_count(s.NumVertices(), 0);
  for (int x = 0; x < 2 * num_edges; ++x) {
    if (fans.Find(x) == x) ++fan_count[edges[x / 2][x % 2]];
  }
  int count = 0;
  for (int i = 0; i < s.NumVertices(); ++i) {
    if (fan_count[i] > 1) {
      ++count;
      examples->Add(std::to_string(i));
    }
  }
  return count;
}

// Faces that appear flipped on an orientable mesh: per orientation component (the parity sets of
// the proper faces), the smaller side is the one to flip.
int CountFlippedFaces(const std::vector<char>& proper, ParitySets* orientation) {
  const int nf = static_cast<int>(proper.size());
  std::vector<int> size(nf, 0), odd(nf, 0);
  for (int f = 0; f < nf; ++f) {
    if (!proper[f]) continue;
    int parity;
    const int root = orientation->Find(f, &parity);
    ++size[root];
    odd[root] += parity;
  }
  int flipped = 0;
  for (int f = 0; f < nf; ++f) flipped += std::min(odd[f], size[f] - odd[f]);
  return flipped;
}

// The report's issue lines, each with its count and up to max_examples examples.
std::vector<std::string> Issues(const MeshReport& r, const Examples& invalid,
                                const Examples& nonfinite, const Examples& degenerate,
                                const Examples& duplicate, const Examples& nm_edges,
                                const Examples& nm_vertices, const Examples& unreferenced) {
  std::vector<std::string> issues;
  auto add = [&issues](const std::string& what, int count, const std::string& suffix) {
    if (count > 0) issues.push_back(what + ": " + std::to_string(count) + suffix);
  };
  add("faces with vertex ids out of range", r.invalid_faces, invalid.Suffix("faces"));
  add("vertices with NaN/Inf coordinates", r.nonfinite_vertices, nonfinite.Suffix("vertices"));
  add("degenerate (zero-area) faces", r.degenerate_faces, degenerate.Suffix("faces"));
  add("duplicate faces", r.duplicate_faces, duplicate.Suffix("face=earlier face"));
  add("non-manifold edges", r.non_manifold_edges, nm_edges.Suffix("edges"));
  add("non-manifold vertices", r.non_manifold_vertices, nm_vertices.Suffix("vertices"));
  add("boundary edges", r.boundary_edges,
      " in " + std::to_string(r.boundary_loops) + (r.boundary_loops == 1 ? " loop" : " loops"));
  if (r.components > 1) add("connected components", r.components, "");
  if (!r.orientable) {
    issues.push_back("non-orientable: no consistent face orientation exists (" +
                     std::to_string(r.inconsistent_edges) + " inconsistent edges)");
  } else {
    add("inconsistently oriented edges", r.inconsistent_edges,
        " (" + std::to_string(r.flipped_faces) + " faces appear flipped)");
  }
  add("unreferenced vertices", r.unreferenced_vertices, unreferenced.Suffix("vertices"));
  return issues;
}

}  // namespace

bool ValidationOptions::IsValid(std::string* error) const {
  if (!(degenerate_tolerance >= 0.0)) {
    *error = "degenerate_tolerance must be >= 0";
    return false;
  }
  if (max_examples < 0) {
    *error = "max_examples must be >= 0";
    return false;
  }
  return true;
}

MeshReport ValidateMesh(const Surface& s, const std::string& name,
                        const ValidationOptions& options) {
  std::string options_error;
  if (!options.IsValid(&options_error)) throw ConfigError("ValidationOptions: " + options_error);
  const int nv = s.NumVertices(), nf = s.NumFaces(), kx = options.max_examples;
  MeshReport r;
  r.name = name;
  r.num_vertices = nv;
  r.num_faces = nf;

  Examples nonfinite(kx), invalid(kx), degenerate(kx), duplicate(kx), unreferenced(kx),
      nm_edges(kx), nm_vertices(kx);
  for (int i = 0; i < nv; ++i) {
    if (!s.V.row(i).allFinite()) {
      ++r.nonfinite_vertices;
      nonfinite.Add(std::to_string(i));
    }
  }

  // Per-face checks; `proper` faces (valid ids, three distinct vertices) carry the topology.
  std::vector<char> referenced(nv, 0), proper(nf, 0);
  std::vector<std::array<int, 4>> sorted_faces;  // sorted vertex ids + face id
  sorted_faces.reserve(nf);
  for (int f = 0; f < nf; ++f) {
    const int a = s.F(f, 0), b = s.F(f, 1), c = s.F(f, 2);
    if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= nv) {
      ++r.invalid_faces;
      invalid.Add(std::to_string(f));
      continue;
    }
    referenced[a] = referenced[b] = referenced[c] = 1;
    std::array<int, 4> key = {a, b, c, f};
    std::sort(key.begin(), key.begin() + 3);
    sorted_faces.push_back(key);
    const Eigen::Vector3d pa = s.V.row(a), pb = s.V.row(b), pc = s.V.row(c);
    const double twice_area = (pb - pa).cross(pc - pa).norm();
    const double longest_sq =
        std::max({(pb - pa).squaredNorm(), (pc - pb).squaredNorm(), (pa - pc).squaredNorm()});
    if (std::isfinite(twice_area)) r.total_area += 0.5 * twice_area;
    const bool repeats = a == b || b == c || a == c;
    if (repeats || twice_area <= options.degenerate_tolerance * longest_sq) {
      ++r.degenerate_faces;
      degenerate.Add(std::to_string(f));
    }
    proper[f] = !repeats;
  }
  std::sort(sorted_faces.begin(), sorted_faces.end());
  for (size_t i = 1; i < sorted_faces.size(); ++i) {
    const auto& p = sorted_faces[i - 1];
    const auto& q = sorted_faces[i];
    if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) {
      ++r.duplicate_faces;
      duplicate.Add(std::to_string(q[3]) + "=" + std::to_string(p[3]));
    }
  }
  for (int i = 0; i < nv; ++i) {
    if (!referenced[i]) {
      ++r.unreferenced_vertices;
      unreferenced.Add(std::to_string(i));
    }
  }

  // Undirected edges: sort the half-edges of the proper faces by their vertex pair.
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(3 * static_cast<size_t>(nf));
  int num_proper = 0;
  for (int f = 0; f < nf; ++f) {
    if (!proper[f]) continue;
    ++num_proper;
    for (int k = 0; k < 3; ++k) {
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3);
      half_edges.push_back({std::min(u, v), std::max(u, v), f, k, u < v});
    }
  }
  std::sort(half_edges.begin(), half_edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.face < y.face;
  });
  std::vector<int> face_edge(3 * static_cast<size_t>(nf), -1);  // edge id per face corner
  std::vector<std::array<int, 2>> edges;                        // endpoints per edge id
  DisjointSets boundary_sets(nv), vertex_sets(nv);
  ParitySets orientation(nf);
  std::vector<char> on_boundary(nv, 0);
  for (size_t i = 0; i < half_edges.size();) {
    size_t j = i;
    while (j < half_edges.size() && half_edges[j].lo == half_edges[i].lo &&
           half_edges[j].hi == half_edges[i].hi) {
      ++j;
    }
    const int e = static_cast<int>(edges.size());
    const int lo = half_edges[i].lo, hi = half_edges[i].hi;
    edges.push_back({lo, hi});
    for (size_t k = i; k < j; ++k) face_edge[3 * half_edges[k].face + half_edges[k].corner] = e;
    vertex_sets.Union(lo, hi);
    const size_t n = j - i;
    if (n == 1) {
      ++r.boundary_edges;
      boundary_sets.Union(lo, hi);
      on_boundary[lo] = on_boundary[hi] = 1;
    } else if (n > 2) {
      ++r.non_manifold_edges;
      nm_edges.Add(std::to_string(lo) + "-" + std::to_string(hi));
    } else {
      const bool same_direction = half_edges[i].forward == half_edges[i + 1].forward;
      if (same_direction) ++r.inconsistent_edges;
      if (!orientation.Relate(half_edges[i].face, half_edges[i + 1].face, same_direction)) {
        r.orientable = false;
      }
    }
    i = j;
  }
  r.num_edges = static_cast<int>(edges.size());

  r.non_manifold_vertices = CountNonManifoldVertices(s, proper, face_edge, edges, &nm_vertices);

  // Faces that repeat a vertex still connect their vertices.
  for (int f = 0; f < nf; ++f) {
    if (proper[f] || s.F.row(f).minCoeff() < 0 || s.F.row(f).maxCoeff() >= nv) continue;
    vertex_sets.Union(s.F(f, 0), s.F(f, 1));
    vertex_sets.Union(s.F(f, 1), s.F(f, 2));
  }
  int num_referenced = 0;
  for (int i = 0; i < nv; ++i) {
    num_referenced += referenced[i];
    if (referenced[i] && vertex_sets.Find(i) == i) ++r.components;
    if (on_boundary[i] && boundary_sets.Find(i) == i) ++r.boundary_loops;
  }

  if (r.orientable) r.flipped_faces = CountFlippedFaces(proper, &orientation);

  r.euler_characteristic = num_referenced - r.num_edges + num_proper;
  r.closed_manifold = num_proper > 0 && num_proper == nf && r.boundary_edges == 0 &&
                      r.non_manifold_edges == 0 && r.non_manifold_vertices == 0;
  if (r.closed_manifold && r.orientable && (2 * r.components - r.euler_characteristic) % 2 == 0) {
    r.genus = (2 * r.components - r.euler_characteristic) / 2;
  }

  r.issues =
      Issues(r, invalid, nonfinite, degenerate, duplicate, nm_edges, nm_vertices, unreferenced);
  return r;
}

std::string MeshReport::ToString() const {
  char area[32];
  std::snprintf(area, sizeof(area), "%.6g", total_area);
  std::string out = name + ": " + std::to_string(num_vertices) + " vertices, " +
                    std::to_string(num_faces) + " faces, area " + area + ", ";
  if (closed_manifold) {
    out += "closed";
    if (genus >= 0) out += ", genus " + std::to_string(genus);
  } else {
    out += (non_manifold_edges > 0 || non_manifold_vertices > 0) ? "non-manifold" : "open";
  }
  if (clean()) return out + ": clean\n";
  out += ": " + std::to_string(issues.size()) + (issues.size() == 1 ? " issue\n" : " issues\n");
  for (const auto& issue : issues) out += "  " + issue + "\n";
  return out;
}

}  // namespace symembed

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

namespace {

// The examples of each kind of issue, listed in the report's messages.
struct IssueExamples {
  explicit IssueExamples(int k)
      : nonfinite(k), invalid(k), degenerate(k), duplicate(k), unreferenced(k), nm_edges(k),
        nm_vertices(k) {}
  Examples nonfinite, invalid, degenerate, duplicate, unreferenced, nm_edges, nm_vertices;
};

// Per-face checks: vertex ids in range, area, degenerate and duplicate faces. Marks the vertices
// the faces reference and the faces that are proper (valid ids, three distinct vertices: they
// carry the topology).
void CheckFaces(const Surface& s, const ValidationOptions& options, MeshReport* r,
                IssueExamples* examples, std::vector<char>* referenced,
                std::vector<char>* proper) {
  const int nv = s.NumVertices(), nf = s.NumFaces();
  referenced->assign(nv, 0);
  proper->assign(nf, 0);
  std::vector<std::array<int, 4>> sorted_faces;  // sorted vertex ids + face id
  sorted_faces.reserve(nf);
  for (int f = 0; f < nf; ++f) {
    const int a = s.F(f, 0), b = s.F(f, 1), c = s.F(f, 2);
    if (std::min({a, b, c}) < 0 || std::max({a, b, c}) >= nv) {
      ++r->invalid_faces;
      examples->invalid.Add(std::to_string(f));
      continue;
    }
    (*referenced)[a] = (*referenced)[b] = (*referenced)[c] = 1;
    std::array<int, 4> key = {a, b, c, f};
    std::sort(key.begin(), key.begin() + 3);
    sorted_faces.push_back(key);
    const Eigen::Vector3d pa = s.V.row(a), pb = s.V.row(b), pc = s.V.row(c);
    const double twice_area = (pb - pa).cross(pc - pa).norm();
    const double longest_sq =
        std::max({(pb - pa).squaredNorm(), (pc - pb).squaredNorm(), (pa - pc).squaredNorm()});
    if (std::isfinite(twice_area)) r->total_area += 0.5 * twice_area;
    const bool repeats = a == b || b == c || a == c;
    if (repeats || twice_area <= options.degenerate_tolerance * longest_sq) {
      ++r->degenerate_faces;
      examples->degenerate.Add(std::to_string(f));
    }
    (*proper)[f] = !repeats;
  }
  std::sort(sorted_faces.begin(), sorted_faces.end());
  for (size_t i = 1; i < sorted_faces.size(); ++i) {
    const auto& p = sorted_faces[i - 1];
    const auto& q = sorted_faces[i];
    if (p[0] == q[0] && p[1] == q[1] && p[2] == q[2]) {
      ++r->duplicate_faces;
      examples->duplicate.Add(std::to_string(q[3]) + "=" + std::to_string(p[3]));
    }
  }
}

// The undirected edges of the proper faces and what they connect.
struct EdgeScan {
  EdgeScan(int nv, int nf)
      : face_edge(3 * static_cast<size_t>(nf), -1),
        boundary_sets(nv),
        vertex_sets(nv),
        orientation(nf),
        on_boundary(nv, 0) {}
  std::vector<int> face_edge;              // edge id per face corner
  std::vector<std::array<int, 2>> edges;  // endpoints per edge id
  DisjointSets boundary_sets, vertex_sets;
  ParitySets orientation;  // of the proper faces, related across their manifold edges
  std::vector<char> on_boundary;
  int num_proper = 0;
};

// Sorts the half-edges of the proper faces by their vertex pair into edges, counting boundary,
// non-manifold and inconsistently oriented edges in *r (and whether it is orientable).
EdgeScan ScanEdges(const Surface& s, const std::vector<char>& proper, MeshReport* r,
                   Examples* nm_edges) {
  const int nv = s.NumVertices(), nf = s.NumFaces();
  EdgeScan scan(nv, nf);
  std::vector<HalfEdge> half_edges;
  half_edges.reserve(3 * static_cast<size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    if (!proper[f]) continue;
    ++scan.num_proper;
    for (int k = 0; k < 3; ++k) {
      const int u = s.F(f, k), v = s.F(f, (k + 1) % 3);
      half_edges.push_back({std::min(u, v), std::max(u, v), f, k, u < v});
    }
  }
  std::sort(half_edges.begin(), half_edges.end(), [](const HalfEdge& x, const HalfEdge& y) {
    return x.lo != y.lo ? x.lo < y.lo : x.hi != y.hi ? x.hi < y.hi : x.face < y.face;
  });
  for (size_t i = 0; i < half_edges.size();) {
    size_t j = i;
    while (j < half_edges.size() && half_edges[j].lo == half_edges[i].lo &&
           half_edges[j].hi == half_edges[i].hi) {
      ++j;
    }
    const int e = static_cast<int>(scan.edges.size());
    const int lo = half_edges[i].lo, hi = half_edges[i].hi;
    scan.edges.push_back({lo, hi});
    for (size_t k = i; k < j; ++k) {
      scan.face_edge[3 * half_edges[k].face + half_edges[k].corner] = e;
    }
    scan.vertex_sets.Union(lo, hi);
    const size_t n = j - i;
    if (n == 1) {
      ++r->boundary_edges;
      scan.boundary_sets.Union(lo, hi);
      scan.on_boundary[lo] = scan.on_boundary[hi] = 1;
    } else if (n > 2) {
      ++r->non_manifold_edges;
      nm_edges->Add(std::to_string(lo) + "-" + std::to_string(hi));
    } else {
      const bool same_direction = half_edges[i].forward == half_edges[i + 1].forward;
      if (same_direction) ++r->inconsistent_edges;
      if (!scan.orientation.Relate(half_edges[i].face, half_edges[i + 1].face, same_direction)) {
        r->orientable = false;
      }
    }
    i = j;
  }
  return scan;
}

}  // namespace

MeshReport ValidateMesh(const Surface& s, const std::string& name,
                        const ValidationOptions& options) {
  std::string options_error;
  if (!options.IsValid(&options_error)) throw ConfigError("ValidationOptions: " + options_error);
  const int nv = s.NumVertices(), nf = s.NumFaces();
  MeshReport r;
  r.name = name;
  r.num_vertices = nv;
  r.num_faces = nf;

  IssueExamples examples(options.max_examples);
  for (int i = 0; i < nv; ++i) {
    if (!s.V.row(i).allFinite()) {
      ++r.nonfinite_vertices;
      examples.nonfinite.Add(std::to_string(i));
    }
  }
  std::vector<char> referenced, proper;
  CheckFaces(s, options, &r, &examples, &referenced, &proper);
  for (int i = 0; i < nv; ++i) {
    if (!referenced[i]) {
      ++r.unreferenced_vertices;
      examples.unreferenced.Add(std::to_string(i));
    }
  }

  EdgeScan scan = ScanEdges(s, proper, &r, &examples.nm_edges);
  r.num_edges = static_cast<int>(scan.edges.size());
  r.non_manifold_vertices =
      CountNonManifoldVertices(s, proper, scan.face_edge, scan.edges, &examples.nm_vertices);

  // Faces that repeat a vertex still connect their vertices.
  for (int f = 0; f < nf; ++f) {
    if (proper[f] || s.F.row(f).minCoeff() < 0 || s.F.row(f).maxCoeff() >= nv) continue;
    scan.vertex_sets.Union(s.F(f, 0), s.F(f, 1));
    scan.vertex_sets.Union(s.F(f, 1), s.F(f, 2));
  }
  int num_referenced = 0;
  for (int i = 0; i < nv; ++i) {
    num_referenced += referenced[i];
    if (referenced[i] && scan.vertex_sets.Find(i) == i) ++r.components;
    if (scan.on_boundary[i] && scan.boundary_sets.Find(i) == i) ++r.boundary_loops;
  }

  if (r.orientable) r.flipped_faces = CountFlippedFaces(proper, &scan.orientation);

  r.euler_characteristic = num_referenced - r.num_edges + scan.num_proper;
  r.closed_manifold = scan.num_proper > 0 && scan.num_proper == nf && r.boundary_edges == 0 &&
                      r.non_manifold_edges == 0 && r.non_manifold_vertices == 0;
  if (r.closed_manifold && r.orientable && (2 * r.components - r.euler_characteristic) % 2 == 0) {
    r.genus = (2 * r.components - r.euler_characteristic) / 2;
  }

  r.issues = Issues(r, examples.invalid, examples.nonfinite, examples.degenerate,
                    examples.duplicate, examples.nm_edges, examples.nm_vertices,
                    examples.unreferenced);
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

#include "stages/preprocess/standard.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <sstream>
#include <tuple>
#include <vector>

#include "core/errors.h"
#include "core/handles.h"

namespace symembed {

namespace {

using Face = std::array<int, 3>;

double FaceDoubleArea(const Eigen::MatrixX3d& V, const Face& f) {
  const Eigen::Vector3d e1 = V.row(f[1]) - V.row(f[0]), e2 = V.row(f[2]) - V.row(f[0]);
  return e1.cross(e2).norm();
}

int Find(std::vector<int>& parent, int x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// Step 0: the faces with boundary vertices at exactly the same position merged into the first
// of them. A triangle soup, or a mesh cut along texture seams, has its copies on boundary
// edges; copies inside the surface are left apart, since merging them would pinch two sheets
// that only touch.
std::vector<Face> WeldBoundaryDuplicates(const Surface& in, bool weld, Report* report) {
  std::vector<Face> faces(in.NumFaces());
  for (int f = 0; f < in.NumFaces(); ++f) faces[f] = {in.F(f, 0), in.F(f, 1), in.F(f, 2)};
  int welded = 0;
  if (weld) {
    std::vector<std::pair<int, int>> edges;
    for (const Face& f : faces) {
      for (int k = 0; k < 3; ++k) {
        edges.emplace_back(std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3]));
      }
    }
    std::sort(edges.begin(), edges.end());
    std::vector<int> boundary;
    for (size_t i = 0; i < edges.size();) {
      size_t j = i;
      while (j < edges.size() && edges[j] == edges[i]) ++j;
      if (j - i == 1) {
        boundary.push_back(edges[i].first);
        boundary.push_back(edges[i].second);
      }
      i = j;
    }
    std::sort(boundary.begin(), boundary.end());
    boundary.erase(std::unique(boundary.begin(), boundary.end()), boundary.end());
    auto position = [&](int v) { return std::make_tuple(in.V(v, 0), in.V(v, 1), in.V(v, 2)); };
    std::sort(boundary.begin(), boundary.end(), [&](int a, int b) {
      return std::make_tuple(position(a), a) < std::make_tuple(position(b), b);
    });
    std::vector<int> representative(in.NumVertices());
    std::iota(representative.begin(), representative.end(), 0);
    for (size_t i = 1; i < boundary.size(); ++i) {
      if (position(boundary[i]) == position(boundary[i - 1])) {
        representative[boundary[i]] = representative[boundary[i - 1]];
        ++welded;
      }
    }
    for (Face& f : faces) {
      for (int& v : f) v = representative[v];
    }
  }
  report->emplace_back("welded_vertices", welded);
  return faces;
}

// Step 1: non-degenerate faces, each vertex set once.
std::vector<Face> CleanFaces(const Surface& in, const std::vector<Face>& input_faces,
                             double tolerance, Report* report) {
  std::vector<Face> faces;
  int degenerate = 0;
  for (const Face& face : input_faces) {
    if (face[0] == face[1] || face[1] == face[2] || face[0] == face[2]) {
      ++degenerate;
      continue;
    }
    double longest = 0.0;
    for (int k = 0; k < 3; ++k) {
      longest = std::max(longest, (in.V.row(face[k]) - in.V.row(face[(k + 1) % 3])).squaredNorm());
    }
    if (0.5 * FaceDoubleArea(in.V, face) <= tolerance * longest) {
      ++degenerate;
      continue;
    }
    faces.push_back(face);
  }
  // Duplicates: sort (vertex set, position) pairs and keep the first of each run.
  std::vector<std::pair<Face, int>> keys(faces.size());
  for (size_t i = 0; i < faces.size(); ++i) {
    Face key = faces[i];
    std::sort(key.begin(), key.end());
    keys[i] = {key, static_cast<int>(i)};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<char> keep(faces.size(), 1);
  for (size_t i = 1; i < keys.size(); ++i) {
    if (keys[i].first == keys[i - 1].first) keep[keys[i].second] = 0;
  }
  std::vector<Face> unique;
  for (size_t i = 0; i < faces.size(); ++i) {
    if (keep[i]) unique.push_back(faces[i]);
  }
  report->emplace_back("degenerate_faces", degenerate);
  report->emplace_back("duplicate_faces", static_cast<double>(faces.size() - unique.size()));
  return unique;
}

// Step 2: the faces of the largest vertex-connected component (by area). Throws
// InvalidInputError when the others hold more than max_removed_area of the area.
std::vector<Face> LargestComponent(const Eigen::MatrixX3d& V, const std::vector<Face>& faces,
                                   bool keep_largest, double max_removed_area, Report* report) {
  std::vector<int> parent(V.rows());
  std::iota(parent.begin(), parent.end(), 0);
  for (const Face& f : faces) {
    parent[Find(parent, f[1])] = Find(parent, f[0]);
    parent[Find(parent, f[2])] = Find(parent, f[0]);
  }
  std::vector<double> area(V.rows(), 0.0);
  for (const Face& f : faces) area[Find(parent, f[0])] += FaceDoubleArea(V, f);
  int components = 0, best = -1;
  for (int v = 0; v < V.rows(); ++v) {
    if (parent[v] != v || area[v] == 0.0) continue;
    ++components;
    if (best < 0 || area[v] > area[best]) best = v;
  }
  std::vector<Face> kept;
  double total = 0.0, removed = 0.0;
  for (const Face& f : faces) {
    const double a = FaceDoubleArea(V, f);
    total += a;
    if (!keep_largest || Find(parent, f[0]) == best) {
      kept.push_back(f);
    } else {
      removed += a;
    }
  }
  const double fraction = total > 0.0 ? removed / total : 0.0;
  if (fraction > max_removed_area) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "preprocess: the mesh has %d connected components and keeping the largest "
                  "would remove %.1f%% of its area (%zu of %zu faces; max_removed_area is "
                  "%.1f%%): is the surface in pieces?",
                  components, 100.0 * fraction, faces.size() - kept.size(), faces.size(),
                  100.0 * max_removed_area);
    throw InvalidInputError(text);
  }
  report->emplace_back("components", components);
  report->emplace_back("removed_component_faces", static_cast<double>(faces.size() - kept.size()));
  report->emplace_back("removed_component_area", fraction);
  return kept;
}

// Step 3: consistent orientation per edge-connected patch; flips faces in place.
void Orient(const Eigen::MatrixX3d& V, std::vector<Face>* faces_ptr, bool orient, Report* report) {
  std::vector<Face>& faces = *faces_ptr;
  const int nf = static_cast<int>(faces.size());
  struct EdgeUse {
    int a, b, face;
    bool forward;  // the face runs a -> b (a < b)
    bool operator<(const EdgeUse& o) const {
      return std::tie(a, b, face) < std::tie(o.a, o.b, o.face);
    }
  };
  std::vector<EdgeUse> uses;
  uses.reserve(3 * nf);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int u = faces[f][k], w = faces[f][(k + 1) % 3];
      uses.push_back({std::min(u, w), std::max(u, w), f, u < w});
    }
  }
  std::sort(uses.begin(), uses.end());
  // Neighbours across manifold edges, with whether both faces run the edge the same way.
  std::vector<std::vector<std::pair<int, bool>>> nbrs(nf);
  std::vector<char> open(nf, 0);
  std::vector<std::array<int, 2>> manifold_pairs;
  int boundary = 0, non_manifold = 0;
  for (size_t i = 0; i < uses.size();) {
    size_t j = i;
    while (j < uses.size() && uses[j].a == uses[i].a && uses[j].b == uses[i].b) ++j;
    if (j - i == 2) {
      const EdgeUse &x = uses[i], &y = uses[i + 1];
      nbrs[x.face].emplace_back(y.face, x.forward == y.forward);
      nbrs[y.face].emplace_back(x.face, x.forward == y.forward);
      manifold_pairs.push_back({static_cast<int>(i), static_cast<int>(i + 1)});
    } else {
      (j - i == 1 ? boundary : non_manifold) += 1;
      for (size_t k = i; k < j; ++k) open[uses[k].face] = 1;
    }
    i = j;
  }
  std::vector<char> flip(nf, 0);
  int conflicts = 0, flipped = 0;
  if (orient) {
    std::vector<int> patch(nf, -1);
    int num_patches = 0;
    for (int seed = 0; seed < nf; ++seed) {
      if (patch[seed] >= 0) continue;
      const int id = num_patches++;
      std::vector<int> members{seed};
      patch[seed] = id;
      for (size_t head = 0; head < members.size(); ++head) {
        const int f = members[head];
        for (const auto& [g, same] : nbrs[f]) {
          if (patch[g] >= 0) continue;
          patch[g] = id;
          flip[g] = flip[f] ^ static_cast<char>(same);
          members.push_back(g);
        }
      }
      // Closed patch: outward orientation; open patch: the majority's input orientation.
      bool closed = true;
      int num_flipped = 0;
      double volume = 0.0;
      for (int f : members) {
        closed = closed && !open[f];
        num_flipped += flip[f];
        const Eigen::Vector3d p0 = V.row(faces[f][0]), p1 = V.row(faces[f][1]),
                              p2 = V.row(faces[f][2]);
        const double signed_volume = p0.dot(p1.cross(p2)) / 6.0;
        volume += flip[f] ? -signed_volume : signed_volume;
      }
      const bool invert =
          closed ? volume < 0.0 : 2 * num_flipped > static_cast<int>(members.size());
      if (invert) {
        for (int f : members) flip[f] ^= 1;
      }
    }
    for (const auto& [i, j] : manifold_pairs) {
      if ((uses[i].forward ^ flip[uses[i].face]) == (uses[j].forward ^ flip[uses[j].face])) {
        ++conflicts;
      }
    }
    for (int f = 0; f < nf; ++f) {
      if (flip[f]) {
        std::swap(faces[f][1], faces[f][2]);
        ++flipped;
      }
    }
  }
  report->emplace_back("flipped_faces", flipped);
  report->emplace_back("orientation_conflicts", conflicts);
  report->emplace_back("non_manifold_edges", non_manifold);
  report->emplace_back("boundary_edges", boundary);
}

// Step 3b: cut the handles of a surface that should be genus 0 (topological noise). Vertices a
// cut leaves without a face are dropped by step 4 like any unreferenced vertex.
void CutTopologicalNoise(const Eigen::MatrixX3d& V, std::vector<Face>* faces, bool cut, bool cap,
                         Report* report) {
  Surface surface;
  surface.V = V;
  surface.F.resize(static_cast<int>(faces->size()), 3);
  for (size_t f = 0; f < faces->size(); ++f) {
    surface.F.row(f) << (*faces)[f][0], (*faces)[f][1], (*faces)[f][2];
  }
  if (!cut) {
    report->emplace_back("genus", SurfaceGenus(surface));
    return;
  }
  HandleCutOptions options;
  options.cap = cap;
  const HandleCutResult r = CutHandles(surface, options);
  report->emplace_back("genus", r.genus_before);
  report->emplace_back("handles_cut", r.cuts);
  report->emplace_back("handle_faces_removed", r.removed_faces);
  report->emplace_back("handle_vertices_removed", r.removed_vertices);
  report->emplace_back("handle_loops_capped", r.capped_loops);
  if (r.cuts == 0) return;
  faces->resize(r.F.rows());
  for (int f = 0; f < r.F.rows(); ++f) (*faces)[f] = {r.F(f, 0), r.F(f, 1), r.F(f, 2)};
}

}  // namespace

PreprocessResult StandardPreprocess(const Surface& in, const StandardPreprocessOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw ConfigError("preprocess/standard: " + error);
  const int nv = in.NumVertices();
  for (int v = 0; v < nv; ++v) {
    if (!in.V.row(v).allFinite()) {
      std::ostringstream text;
      text << "preprocess: vertex " << v << " (0-based) has non-finite coordinates ("
           << in.V(v, 0) << ", " << in.V(v, 1) << ", " << in.V(v, 2) << ")";
      throw InvalidInputError(text.str());
    }
  }
  for (int f = 0; f < in.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) {
      if (in.F(f, k) < 0 || in.F(f, k) >= nv) {
        throw InvalidInputError("preprocess: face " + std::to_string(f) + " has vertex id " +
                                std::to_string(in.F(f, k)) + " outside [0, " + std::to_string(nv) +
                                ")");
      }
    }
  }
  PreprocessResult result;
  Report& report = result.report;
  report.emplace_back("input_vertices", nv);
  report.emplace_back("input_faces", in.NumFaces());
  std::vector<Face> faces = WeldBoundaryDuplicates(in, options.weld_boundary_duplicates, &report);
  faces = CleanFaces(in, faces, options.degenerate_tolerance, &report);
  if (faces.empty()) {
    throw InvalidInputError("preprocess: all " + std::to_string(in.NumFaces()) +
                            " faces are degenerate (a repeated vertex id, or zero area within "
                            "degenerate_tolerance), so no surface is left");
  }
  faces = LargestComponent(in.V, faces, options.keep_largest_component, options.max_removed_area,
                           &report);
  Orient(in.V, &faces, options.orient, &report);
  CutTopologicalNoise(in.V, &faces, options.cut_handles, options.cap_cut_handles, &report);

  // Step 4: keep referenced vertices in input order.
  std::vector<int> new_id(nv, -1);
  for (const Face& f : faces) {
    for (int v : f) new_id[v] = 0;
  }
  for (int v = 0; v < nv; ++v) {
    if (new_id[v] < 0) continue;
    new_id[v] = static_cast<int>(result.input_ids.size());
    result.input_ids.push_back(v);
  }
  const int kept = static_cast<int>(result.input_ids.size());
  Surface& out = result.surface;
  out.V.resize(kept, 3);
  for (int i = 0; i < kept; ++i) out.V.row(i) = in.V.row(result.input_ids[i]);
  out.F.resize(static_cast<int>(faces.size()), 3);
  for (size_t f = 0; f < faces.size(); ++f) {
    out.F.row(f) << new_id[faces[f][0]], new_id[faces[f][1]], new_id[faces[f][2]];
  }
  report.emplace_back("unreferenced_vertices", nv - kept);
  report.emplace_back("output_vertices", kept);
  report.emplace_back("output_faces", out.NumFaces());

  // Step 5: area-weighted centroid to the origin, unit total area.
  const Eigen::VectorXd areas = FaceAreas(out);
  const double area = areas.sum();
  Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
  for (int f = 0; f < out.NumFaces(); ++f) {
    centre +=
        areas(f) * (out.V.row(out.F(f, 0)) + out.V.row(out.F(f, 1)) + out.V.row(out.F(f, 2))) / 3.0;
  }
  centre /= area;
  result.scale = 1.0;
  if (options.normalize) {
    result.scale = 1.0 / std::sqrt(area);
    out.V = (out.V.rowwise() - centre) * result.scale;
  } else {
    centre.setZero();
  }
  report.emplace_back("input_area", area);
  report.emplace_back("scale", result.scale);
  report.emplace_back("centre_x", centre(0));
  report.emplace_back("centre_y", centre(1));
  report.emplace_back("centre_z", centre(2));

  return result;
}

}  // namespace symembed

// The `standard` preprocessing of an input surface, on (V, F) directly so that meshes OpenMesh
// cannot represent (non-manifold edges, flipped neighbours) are repaired too.
//
// Steps, in order, each counted in the report:
//   0. weld boundary vertices at exactly the same position (a triangle soup, a mesh cut along
//      texture seams); copies inside the surface stay apart;
//   1. drop degenerate faces (a repeated vertex id, or area <= degenerate_tolerance * longest
//      edge^2) and duplicate faces (same vertex set in either orientation; the first is kept);
//   2. keep the largest connected component (faces connected through shared vertices; largest
//      by area); the shape fails when the others hold more than max_removed_area of the area;
//   3. make face orientation consistent (breadth-first over faces across manifold edges: a
//      neighbour is flipped when it runs the shared edge in the same direction), then choose
//      each edge-connected patch's orientation: outward (positive signed volume) when the patch
//      is closed, otherwise the orientation of the majority of its input faces;
//   3b. cut the handles (core/handles.h): bodies are genus 0, so a handle is topological noise,
//      touching parts merged by the scan, whose short circuit every geodesic would take; the
//      faces along a short loop around each handle are removed until the genus is 0 (the few
//      vertices a cut leaves without a face go in step 4), and the loops the cuts opened are
//      closed with faces between their own vertices (cap_cut_handles), so that undoing a merge
//      leaves no hole. A genus-0 surface, or one that is not an oriented manifold, is unchanged;
//   4. drop unreferenced vertices (input_ids maps kept vertices to input ids);
//   5. translate the area-weighted centroid to the origin and scale to unit total area.
// Output coordinates are (input - centre) * scale; `scale` and the centre are reported so
// results can be given in input units.
//
// Report keys: input_vertices, input_faces, welded_vertices, degenerate_faces, duplicate_faces,
// components, removed_component_faces, removed_component_area (fraction), flipped_faces, orientation_conflicts (edges still run in the same
// direction by both faces: a non-orientable patch), non_manifold_edges, boundary_edges,
// unreferenced_vertices, output_vertices, output_faces, input_area, scale, centre_x, centre_y,
// centre_z, genus (before step 3b; -1: not an oriented manifold), handles_cut,
// handle_faces_removed, handle_vertices_removed, handle_loops_capped (the last four only with
// cut_handles).
#pragma once

#include <string>

#include "core/mesh.h"
#include "core/range.h"
#include "registry/types.h"

namespace symembed {

struct StandardPreprocessOptions {
  bool orient = true;                   // step 3
  bool weld_boundary_duplicates = true;  // step 0
  bool keep_largest_component = true;   // step 2
  double max_removed_area = 0.05;       // step 2: fraction of the area other components may hold
  static constexpr Range kMaxRemovedArea = Range::Closed(0.0, 1.0);
  bool normalize = true;                // step 5 (centre and unit area)
  double degenerate_tolerance = 1e-12;  // step 1, relative to the longest edge squared
  // A triangle's area is at most sqrt(3)/4 ~ 0.433 times its longest edge squared: a tolerance
  // above that drops every face.
  static constexpr Range kDegenerateTolerance = Range::Closed(0.0, 0.5);
  bool cut_handles = true;              // step 3b
  bool cap_cut_handles = true;          // step 3b: close the loops a cut opens

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("orient", self.orient);
    visit("weld_boundary_duplicates", self.weld_boundary_duplicates);
    visit("keep_largest_component", self.keep_largest_component);
    visit("max_removed_area", self.max_removed_area, kMaxRemovedArea);
    visit("normalize", self.normalize);
    visit("degenerate_tolerance", self.degenerate_tolerance, kDegenerateTolerance);
    visit("cut_handles", self.cut_handles);
    visit("cap_cut_handles", self.cap_cut_handles);
  }
  bool IsValid(std::string* error) const { return NoViolation(FieldViolation(*this), error); }
};

// Throws InvalidInputError (naming the face or vertex) for face ids out of range, non-finite
// coordinates, when no non-degenerate face is left, or when step 2 would remove more than
// max_removed_area of the area.
PreprocessResult StandardPreprocess(const Surface& input,
                                    const StandardPreprocessOptions& options = {});

}  // namespace symembed

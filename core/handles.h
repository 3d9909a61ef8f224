// Cutting the handles of a surface: topological noise removal for shapes that should be genus
// 0 (bodies whose touching parts were merged by the scan or its reconstruction, as in the
// SHREC'16 topology benchmark).
//
// A handle is found as in [Guskov & Wood 2001, "Topological noise removal", Graphics
// Interface]: geodesic balls (Dijkstra along the mesh's edges) grow from every vertex, the first
// `seeds` in farthest-point order, each stopping at the sixth smallest radius found so far;
// a ball's induced subcomplex gains a 1-cycle exactly when its front meets itself (its Euler
// characteristic drops), and that cycle is a handle's when it does not split off a new
// component of the unreached vertices (on a sphere every such cycle separates). Each seed's first
// handle cycle gives a loop through the meeting vertex and the seed's shortest-path tree, a short
// loop around the handle (Erickson & Whittlesey's shortest loop through a basepoint); of the six
// reached at the smallest radii, the one whose cut puts the vertices it separates farthest apart
// (median distance along the cut surface) is cut: a loop around a bridge rather than one
// through two bridges side by side, whose cut would only slit them. The faces along the loop on
// one side of it are removed (the side that leaves fewer vertices without a face, then the side of
// less area), which severs the handle: its genus drops by one and two boundary loops appear.
// No vertex is renumbered; the few a strip leaves without a face (on a thin bridge) become
// unreferenced. A cut that would split the surface or not lower its genus is passed over.
// Repeated until the genus is 0, no handle is found, or max_cuts. Each boundary loop counts as
// filled in, so that a loop around a hole is not taken for a handle. Then the loops the cuts
// opened are closed (HandleCutOptions::cap).
//
// Needs a consistently oriented manifold (every edge in one or two faces, every vertex's faces
// one fan); otherwise nothing is cut and the report says why. A genus-0 surface is returned
// unchanged without any search. Positions are not read except for edge lengths.
#pragma once

#include <string>
#include <vector>

#include "core/mesh.h"

namespace symembed {

struct HandleCutOptions {
  int max_cuts = 32;  // at most this many handles cut
  int seeds = 64;     // balls grown first, from farthest-point seeds (then every vertex)
  // Close each boundary loop the cuts opened with new faces between its own vertices (no vertex
  // is added), so that the surface keeps no hole where a merge was undone: a body whose merged
  // parts were cut apart is whole, not partial. A loop that passes a vertex twice, or whose
  // closing faces would reuse an edge of the surface, stays open.
  bool cap = true;
};

struct HandleCutResult {
  Eigen::MatrixX3i F;    // the faces kept, in input order (input F when nothing was cut)
  int genus_before = 0;  // -1 when the surface is not an oriented manifold
  int genus_after = 0;
  int cuts = 0;  // handles cut
  int removed_faces = 0;
  int removed_vertices = 0;   // vertices the cuts left without a face
  double longest_loop = 0.0;  // the longest cut loop's length (edge lengths summed)
  int capped_loops = 0;       // loops closed (options.cap)
  int cap_faces = 0;          // faces added to close them, after the faces kept in F
  std::string skipped;        // why nothing was searched, when it was not (non-manifold)
};

// The genus of a surface from its Euler characteristic, boundary loops and components
// (2 - 2g = chi + b per component, summed); -1 when some edge has more than two faces.
int SurfaceGenus(const Surface& surface);

HandleCutResult CutHandles(const Surface& surface, const HandleCutOptions& options = {});

}  // namespace symembed

// Mesh validation: counts, topology and defects of a triangle soup (V, F) as loaded from a file.
//
// Works on Surface rather than the half-edge mesh so that nothing is lost: non-manifold,
// duplicate and flipped faces are all counted. Never throws on bad data; faces with vertex ids
// out of range are counted and left out of every other check.
#pragma once

#include <string>
#include <vector>

#include "core/mesh.h"

namespace symembed {

struct ValidationOptions {
  // A face is degenerate when twice its area is at most this times its longest edge squared
  // (i.e. its smallest angle's sine is below the tolerance) or it repeats a vertex id.
  double degenerate_tolerance = 1e-12;
  // Number of example ids listed per defect in the issue lines.
  int max_examples = 3;

  bool IsValid(std::string* error) const;
};

struct MeshReport {
  std::string name;
  int num_vertices = 0;
  int num_faces = 0;
  int num_edges = 0;  // distinct undirected edges of the valid, non-repeating faces

  int invalid_faces = 0;          // faces with a vertex id outside [0, #V)
  int nonfinite_vertices = 0;     // vertices with a NaN or Inf coordinate
  int unreferenced_vertices = 0;  // vertices used by no valid face
  int degenerate_faces = 0;       // zero-area faces (see ValidationOptions)
  int duplicate_faces = 0;        // faces with the vertex set of an earlier face
  int non_manifold_edges = 0;     // edges with more than two incident faces
  int non_manifold_vertices = 0;  // vertices whose incident faces form more than one fan
  int boundary_edges = 0;         // edges with exactly one incident face
  int boundary_loops = 0;         // connected components of the boundary edges
  int components = 0;             // connected components of the faces (sharing a vertex)
  // Manifold edges whose two faces traverse them in the same direction.
  int inconsistent_edges = 0;
  // Whether faces can be re-oriented so that every manifold edge is consistent; when true,
  // flipped_faces is the fewest faces to flip (the smaller side of each component).
  bool orientable = true;
  int flipped_faces = 0;
  double total_area = 0.0;  // sum of the finite face areas
  // V - E + F over referenced vertices, edges and valid faces.
  int euler_characteristic = 0;
  // Whether the mesh is a closed, oriented 2-manifold without defects; genus is then
  // (2 * components - euler_characteristic) / 2, summed over components.
  bool closed_manifold = false;
  int genus = -1;  // -1 unless closed_manifold

  // One line per defect ("non-manifold edges: 3 (e.g. 4-7, 9-12, 13-2)"); empty when clean.
  // Boundaries and several components are listed too: the pipeline assumes one closed surface.
  std::vector<std::string> issues;

  bool clean() const { return issues.empty(); }
  // A header line ("NAME: 5000 vertices, 9996 faces, area 1.2e+04, closed, genus 0: clean")
  // followed by one indented line per issue.
  std::string ToString() const;
};

// Validates a surface. name: shown in ToString (usually the file path).
// Cost: O(#F log #F).
MeshReport ValidateMesh(const Surface& surface, const std::string& name,
                        const ValidationOptions& options = ValidationOptions());

}  // namespace symembed

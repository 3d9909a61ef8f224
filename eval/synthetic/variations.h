// Per-pose variations of the synthetic benchmark: partiality, independent remeshing, noise.
// Each keeps, for every output vertex, the rest vertex it came from, so the ground truth stays
// exact on what remains.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "eval/synthetic/figure.h"

namespace symembed {

// A posed shape: its surface and, per vertex, the rest vertex id it is (rest_ids.size() == #V).
struct TrackedSurface {
  Surface surface;
  std::vector<int> rest_ids;
};

// Cuts away what bone `bone` and its descendants carry: every vertex whose summed skinning
// weight on them is > 0.5 (weights: #rest vertices x #bones), with the faces touching it, then
// vertices left without faces. The shape gets a boundary loop where the part was.
TrackedSurface CutPart(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
                       const std::vector<Bone>& bones, int bone);

// Topological noise, as in scanned bodies whose touching parts merge (TOPKIDS [Lähner et al.
// 2016]): joins the regions where two parts of the body that are not neighbours in the skeleton
// come closest. A face's part is the bone with the largest summed skinning weight of its
// vertices (weights: #rest vertices x #bones); two parts may be glued when their bones are at
// least three bones apart, or two apart without being siblings (a hand and the torso, an arm
// and the hip, two shins; not the two thighs), and when the faces are at least three times
// their gap apart along the surface's edges (a short circuit, not a crease). The closest such
// pair of facing faces is found, then up to max_bridges such pairs whose centroids are within
// that gap plus two mean edge lengths, closest first, vertex-disjoint; each pair of faces is
// replaced by a triangulated tube between them (6 triangles). No vertex is added or moved, so
// rest ids and the ground truth stay exact; each tube adds a handle (genus + 1) and a short
// circuit of the surface. *gap (when given) receives the closest gap found; the shape is
// returned unchanged, with *gap = +inf, when no two such parts face each other.
TrackedSurface GlueParts(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
                         const std::vector<Bone>& bones, int max_bridges, double* gap = nullptr);

// Closes the closest gap GlueParts would bridge: the two regions around it move towards each
// other by half the gap each, fading out smoothly over a graph distance of twice the gap (at
// least three mean edge lengths), so that they touch, as a hand resting on a hip. Vertices
// keep their ids. *gap (when given) receives the gap closed (+inf, shape unchanged: none).
TrackedSurface PullIntoContact(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
                               const std::vector<Bone>& bones, double* gap = nullptr);

// The closest gap GlueParts would bridge (+inf when none).
double GlueGap(const TrackedSurface& shape, const Eigen::MatrixXd& weights,
               const std::vector<Bone>& bones);

// Cuts a hole: removes the faces with a vertex within graph distance `radius` (along the mesh's
// edges, core/mesh_graph.h) of vertex `center`, then vertices left without faces, then every
// connected component but the largest (a hole around a thin limb takes what it severs).
TrackedSurface CutHole(const TrackedSurface& shape, int center, double radius);

// Cuts the shape by the plane normal . x = offset, the offset placed so that a fraction
// `removed` (in [0, 1)) of the vertices lies below it: removes the faces with a vertex below,
// then vertices left without faces, then every connected component but the largest (the one
// partial surface a scanner would see).
TrackedSurface CutByPlane(const TrackedSurface& shape, const Eigen::Vector3d& normal,
                          double removed);

// Independent remeshing by decimation to target_vertices (OpenMesh DecimaterT): halfedge
// collapses only, so every surviving vertex keeps its position and rest id. The collapse order
// is the squared edge length times a random factor in [0.5, 1.5) of the removed vertex (seeded),
// so different seeds keep different vertices; a normal-flip guard (45 degrees) keeps faces from
// folding. Returns fewer collapses than asked when no legal collapse is left.
// With anisotropy a > 1 an edge's length is measured as if the shape were stretched by a along
// the unit vector `direction`, so the edges along it are collapsed last: the result has edges
// shorter along the direction than across it, triangles elongated across it (an anisotropic
// remeshing, as scanners and remeshing tools produce; less anisotropic than a, since collapses
// only remove vertices), and no triangle of aspect ratio above 3 a.
TrackedSurface Remesh(const TrackedSurface& shape, int target_vertices, uint32_t seed,
                      double anisotropy = 1.0,
                      const Eigen::Vector3d& direction = Eigen::Vector3d::UnitX());

// Loop subdivision, `levels` times (OpenMesh LoopT): each level splits every triangle into four,
// a new vertex on every edge, and moves the old vertices by Loop's smoothing rule (a fraction of
// the mean edge length on a smooth surface; boundaries by the 1-6-1 rule). The old vertices keep
// their ids and rest ids; the new ones have rest id -1 (no rest vertex). levels >= 0; throws
// InternalError for a non-manifold input.
TrackedSurface Subdivide(const TrackedSurface& shape, int levels);

// Moves every vertex along its normal by amplitude * mean_edge_length * u, u uniform in
// [-1, 1) (seeded, drawn in vertex order).
void AddNormalNoise(Surface* surface, double amplitude, uint32_t seed);

}  // namespace symembed

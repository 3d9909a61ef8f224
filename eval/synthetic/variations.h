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

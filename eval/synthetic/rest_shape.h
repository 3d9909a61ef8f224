// The rest shape of a synthetic figure: the box model (figure.h) smoothed by Catmull-Clark
// subdivision [Catmull & Clark 1978] (OpenMesh's CatmullClarkT), triangulated, and snapped to
// exact bilateral symmetry, with skinning weights subdivided by the same stencils.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/mesh.h"
#include "eval/synthetic/figure.h"

namespace symembed {

struct RestFigure {
  Figure figure;            // box model and skeleton
  int rings_per_segment = 1;
  int levels = 1;           // Catmull-Clark levels
  // Closed, manifold, consistently oriented (normals outwards), genus 0, and exactly symmetric
  // about x = 0: V.row(mirror[i]) == (-x_i, y_i, z_i) bit for bit, and faces map to faces.
  Surface surface;
  Eigen::MatrixXd weights;  // #V x #bones skinning weights, each row sums to 1
  std::vector<int> mirror;  // #V, an involution
};

// The subdivision parameters whose vertex count (4^levels * quads + 2) is closest to
// target_vertices (relative error; one level only when two levels overshoot badly).
void ChooseResolution(FigureKind kind, int target_vertices, int* rings_per_segment, int* levels);

// Builds the rest shape with about target_vertices vertices (>= 100). Throws InternalError when
// the subdivided mesh is not mirror-symmetric to 1e-9 (a modelling bug).
RestFigure MakeRestFigure(FigureKind kind, int target_vertices);

// The mirror map of V about x = 0: mirror[i] = j with |V_j - (-x_i, y_i, z_i)| <= tolerance;
// -1 where there is no such vertex (or more than one).
std::vector<int> MirrorMap(const Eigen::MatrixX3d& V, double tolerance);

}  // namespace symembed

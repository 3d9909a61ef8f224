// Per-vertex extrinsic curvature features of a triangle mesh, used by the flip scorers.
//
//   mean       H  = (L x)_i . n_i / (2 A_i): the cotan Laplacian of the positions is the mean
//                   curvature normal [Meyer et al. 2003]; positive on a sphere whose faces are
//                   counter-clockwise seen from outside (outward normals), negative on a cup.
//   gaussian   K  = angle defect / A_i (2 pi - sum of corner angles; pi - sum on the boundary,
//                   where it is only a rough estimate) [Meyer et al. 2003].
//   k1, k2        principal curvatures, k1 >= k2, same sign convention as H, from a
//                   least-squares quadric (height function) fit over the neighbourhood in the
//                   tangent frame [Cazals & Pouget 2005] Estimating differential quantities
//                   using polynomial fitting of osculating jets. Unlike H +- sqrt(H^2 - K), this
//                   does not amplify noise at umbilics (spheres stay caps).
//   shape_index S = (2 / pi) atan2(k1 + k2, k1 - k2) in [-1, 1]: +1 cap (sphere, outward
//                   normals), +1/2 ridge (cylinder), 0 saddle, -1/2 rut, -1 cup; 0 where flat
//                   [Koenderink & van Doorn 1992] Surface shape and curvature scales.
//   normals       unit area-weighted vertex normals; zero rows for vertices in no face.
// A_i is the mixed Voronoi vertex area [Meyer et al. 2003]. Units: 1/length for H, k1, k2;
// 1/length^2 for K.
//
// Scale: H and K are averaged (area-weighted) over a neighbourhood of every vertex, and k1, k2
// are fitted over it; the neighbourhood is the k-ring (smoothing_rings; the fit uses at least
// the 2-ring) or, when smoothing_radius > 0, the vertices within edge-graph distance
// smoothing_radius * sqrt(total area). Normals are not smoothed.
//
// [Meyer et al. 2003] Discrete differential-geometry operators for triangulated 2-manifolds.
#pragma once

#include <Eigen/Core>
#include <string>

#include "core/mesh.h"

namespace symembed {

struct CurvatureOptions {
  int smoothing_rings = 2;        // k-ring averaging; 0 = none
  double smoothing_radius = 0.0;  // relative to sqrt(total area); > 0 overrides rings

  bool IsValid(std::string* error) const;
};

struct CurvatureFeatures {
  Eigen::VectorXd mean;         // #V mean curvature H
  Eigen::VectorXd gaussian;     // #V Gaussian curvature K
  Eigen::VectorXd k1, k2;       // #V principal curvatures, k1 >= k2
  Eigen::VectorXd shape_index;  // #V in [-1, 1]
  Eigen::MatrixX3d normals;     // #V unit area-weighted vertex normals
};

// Throws ConfigError for invalid options. Vertices in no face get all-zero features.
CurvatureFeatures ComputeCurvature(const Surface& surface, const CurvatureOptions& options = {});

}  // namespace symembed

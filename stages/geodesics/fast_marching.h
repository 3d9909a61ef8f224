// Geodesic distances by fast marching on triangulated surfaces (`fast_marching`).
//
// [Kimmel & Sethian 1998] Computing geodesic paths on manifolds. The eikonal equation
// |grad T| = 1 is solved by a Dijkstra-like sweep; a vertex C of triangle (C, A, B) is updated
// from A and B once both are accepted, with the planar first-order update written with the
// inverse Gram matrix Q of the edge vectors e_A = A - C, e_B = B - C: T_C = p, the larger root
// of (p 1 - t)^T Q (p 1 - t) = 1 with t = (T_A, T_B), accepted only when it is causal (the
// characteristic reaches C from inside the triangle: Q (p 1 - t) >= 0 componentwise);
// otherwise T_C = min(T_A + |e_A|, T_B + |e_B|).
//
// Obtuse triangles: the update at an obtuse corner C is not causal for characteristics that
// arrive through the obtuse angle, which makes plain fast marching degrade to edge paths there.
// As in Kimmel & Sethian, the obtuse angle is split by a virtual edge C-D to a vertex D found
// by unfolding the neighbouring triangles across the opposite edge into the plane of (C, A, B)
// until one lies in the section of directions that makes both angles ACD and DCB acute; the
// two virtual acute triangles (C, A, D) and (C, D, B) replace (C, A, B) in the updates of C.
// When no such vertex is found within max_unfold_steps (or a boundary is hit), the obtuse
// triangle is kept.
//
// First-order accurate: the error is O(h) in the mean edge length h. Distances are +infinity
// at vertices not connected to the source.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "registry/stages.h"
#include "stages/geodesics/geodesics_common.h"

namespace symembed {

struct FastMarchingOptions {
  GeodesicsCommonOptions common;  // threads, precision
  int max_unfold_steps = 10;      // triangles unfolded per obtuse corner; 0 = no splitting
  static constexpr Range kMaxUnfoldSteps = Range::Closed(0, 1000);

  bool IsValid(std::string* error) const;
};

// Reusable solver: the update stencils (including the virtual triangles of split obtuse
// corners) are built once. Distances() is thread-safe and parallel over sources.
// Throws InvalidInputError for a source id outside [0, #V).
class FastMarchingGeodesicSolver : public GeodesicSolver {
 public:
  FastMarchingGeodesicSolver(const Surface& surface, const FastMarchingOptions& options = {});
  Eigen::MatrixXd Distances(const std::vector<int>& sources) const override;

  int obtuse_corners() const { return obtuse_corners_; }  // corners with angle > 90 deg
  int split_corners() const { return split_corners_; }    // of those, split by unfolding

  // One update of `target` triggered by accepting `v`, using `other` if it is accepted. The
  // coefficients are stored in single precision (28 bytes per update instead of 48: the sweep
  // is bound by memory traffic through this array) and used in double; their relative error
  // of 6e-8 is far below the method's O(h) error.
  struct Update {
    int target;
    int other;
    float q_vv, q_vo, q_oo;  // inverse Gram matrix of (v - target, other - target)
    float len_v, len_o;      // |v - target|, |other - target|
  };

 private:
  template <typename Scalar>
  struct Workspace;
  template <typename Scalar>
  void Solve(int source, Scalar* T, Workspace<Scalar>* ws) const;

  int num_vertices_ = 0;
  std::vector<int> offsets_;  // #V + 1: updates triggered by vertex v
  std::vector<Update> updates_;
  FastMarchingOptions options_;
  int obtuse_corners_ = 0;
  int split_corners_ = 0;
};

// Free-function form: #sources x #V distances.
Eigen::MatrixXd FastMarchingDistances(const Surface& surface, const std::vector<int>& sources,
                                      const FastMarchingOptions& options = {});

}  // namespace symembed

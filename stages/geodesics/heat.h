// Geodesic distances by the heat method (`heat`).
//
// [Crane, Weischedel & Wardetzky 2013] Geodesics in heat: a new approach to computing distance
// based on heat flow. Per source s:
//   1. heat flow for a short time t = time_factor * h^2 (h = mean edge length), one backward
//      Euler step: (M + t K) u = delta_s, with M the lumped mass matrix and K the cotan
//      stiffness matrix (core/laplacian.h);
//   2. X = -grad u / |grad u| per face;
//   3. K phi = -div X (the integrated divergence of the paper), solved up to a constant;
//   4. phi shifted so that phi(s) = 0 (small negative values near s are clamped to 0).
// All operators are built on the intrinsic Delaunay triangulation of the surface
// (core/intrinsic_delaunay.h) unless intrinsic_delaunay is false: on meshes with many obtuse
// triangles (TOSCA's remeshed shapes have ~60%) the extrinsic cotan Laplacian has negative
// weights, the heat solution oscillates in sign and the distances are off by tens of percent
// [Sharp, Soliman & Crane 2019] Navigating intrinsic triangulations.
// With a boundary, step 1 is solved with Neumann (natural) and with Dirichlet (u = 0 on the
// boundary) conditions and the two solutions are averaged, as the paper recommends; `boundary`
// selects one of them instead. K + eps M (eps = 1e-8 / total area) replaces the singular K in
// step 3. One sparse LDL^T factorisation per system (Eigen SimplicialLDLT, AMD ordering) is
// computed in the constructor and reused for every source; sources are solved in blocks, in
// parallel. The heat solution decays like exp(-d / h) away from the source, which underflows
// single precision on large meshes, so `precision: float` is accepted but the solver always
// computes in double. Vertices in no face or not connected to the source get +infinity.
//
// Accuracy: smooth and close to the true distance, but smoothed near the cut locus and
// slightly biased (a few percent) at t = h^2; larger time_factor gives smoother distances.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <memory>
#include <string>
#include <vector>

#include "core/intrinsic_delaunay.h"
#include "core/mesh.h"
#include "registry/stages.h"
#include "stages/geodesics/geodesics_common.h"

namespace symembed {

enum class HeatBoundary { kAverage, kNeumann, kDirichlet };

struct HeatOptions {
  GeodesicsCommonOptions common;                   // threads; precision is accepted, see above
  double time_factor = 1.0;                        // t = time_factor * (mean edge length)^2
  static constexpr Range kTimeFactor = Range::Closed(1e-6, 1e6);
  HeatBoundary boundary = HeatBoundary::kAverage;  // only matters on surfaces with a boundary
  bool intrinsic_delaunay = true;                  // operators on the intrinsic Delaunay mesh

  bool IsValid(std::string* error) const;
};

// Reusable solver; the factorisations are computed once. Throws InvalidInputError for an empty
// surface or bad face ids and SolverError when a factorisation fails.
class HeatGeodesicSolver : public GeodesicSolver {
 public:
  HeatGeodesicSolver(const Surface& surface, const HeatOptions& options = {});
  Eigen::MatrixXd Distances(const std::vector<int>& sources) const override;

  double time() const { return t_; }
  bool has_boundary() const { return has_boundary_; }
  int flips() const { return flips_; }  // intrinsic edge flips performed

 private:
  // Distances of a block of sources, written to out (n x block, column-major).
  void SolveBlock(const int* sources, int count, Eigen::MatrixXd* out) const;

  using Factor = Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>;
  Surface surface_;
  HeatOptions options_;
  double t_ = 0.0;
  bool has_boundary_ = false;
  int flips_ = 0;
  Eigen::MatrixX3i faces_;  // faces of the (intrinsic) triangulation the operators live on
  // neumann_ is always built (it also tells which vertices the heat reaches); dirichlet_ only
  // when the surface has a boundary and the boundary option uses it.
  std::unique_ptr<Factor> neumann_, dirichlet_, poisson_;
  std::vector<char> boundary_vertex_, used_vertex_;
  // Per face, in its own 2D layout: gradient basis vectors (grad u = sum_k u_k G_k) and
  // divergence weights (a face vector X adds W_k . X to vertex k's integrated divergence).
  Eigen::MatrixX2d grad_[3], div_[3];  // each #F x 2
};

// Free-function form: #sources x #V distances.
Eigen::MatrixXd HeatDistances(const Surface& surface, const std::vector<int>& sources,
                              const HeatOptions& options = {});

}  // namespace symembed

#include <Eigen/SparseCholesky>
#include <cmath>

#include "core/curvature.h"
#include "core/errors.h"
#include "core/laplacian.h"
#include "stages/flip/extrinsic.h"

namespace symembed {

Eigen::MatrixXd ExtrinsicFeatures(const Surface& surface, const FeatureSmoothing& smoothing) {
  if (surface.NumVertices() == 0 || surface.NumFaces() == 0) {
    throw InvalidInputError("flip extrinsic: empty surface");
  }
  CurvatureOptions options;
  options.smoothing_rings = smoothing.rings;
  options.smoothing_radius = smoothing.radius;
  const CurvatureFeatures c = ComputeCurvature(surface, options);
  const Eigen::VectorXd areas = VertexAreas(surface);
  const double total = areas.sum();
  if (!(total > 0.0)) throw InvalidInputError("flip extrinsic: surface of zero area");
  const double unit = std::sqrt(total);
  Eigen::MatrixXd F(surface.NumVertices(), 3);
  F.col(0) = c.shape_index;
  const Eigen::ArrayXd curvedness = ((c.k1.array().square() + c.k2.array().square()) / 2.0).sqrt();
  F.col(1) = (1.0 + curvedness * unit).log().matrix();
  F.col(2) = areas / total;
  return F;
}

Eigen::MatrixXd DiffuseFeatures(const Surface& surface, const Eigen::MatrixXd& F, double time) {
  if (!(time > 0.0 && std::isfinite(time))) {
    throw ConfigError("flip extrinsic: the diffusion time must be > 0 and finite, got " +
                      std::to_string(time));
  }
  if (F.rows() != surface.NumVertices() || F.cols() != 3) {
    throw InvalidInputError("flip extrinsic: features do not match the surface to diffuse them on");
  }
  const Eigen::SparseMatrix<double> M = MassMatrix(surface);
  const double area = M.sum();
  const Eigen::SparseMatrix<double> system = M + (time * area) * CotanStiffness(surface);
  // Vertices in no face have zero mass and stiffness; they keep their features.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver;
  Eigen::SparseMatrix<double> regular = system;
  for (int v = 0; v < surface.NumVertices(); ++v) {
    if (M.coeff(v, v) <= 0.0) regular.coeffRef(v, v) += 1.0;
  }
  solver.compute(regular);
  if (solver.info() != Eigen::Success) {
    throw InvalidInputError(
        "flip extrinsic: the heat diffusion of the features cannot be factored");
  }
  Eigen::MatrixXd out = F;
  for (int f = 0; f < 2; ++f) {
    Eigen::VectorXd rhs = M * F.col(f);
    for (int v = 0; v < surface.NumVertices(); ++v) {
      if (M.coeff(v, v) <= 0.0) rhs(v) = F(v, f);
    }
    out.col(f) = solver.solve(rhs);
  }
  return out;
}

}  // namespace symembed

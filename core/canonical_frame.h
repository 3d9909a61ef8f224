// The canonical frame of a symmetrized embedding.
//
// [Yoshiyasu et al. 2016] Symmetry-aware embedding for shape correspondence: once an embedding is
// symmetric about x = 0, the frame is fixed up to the four proper rotations {I, Rx(pi), Ry(pi),
// Rz(pi)} (CandidateRotations in registry/types.h), which the flip stage resolves.
#pragma once

#include <Eigen/Core>

namespace symembed {

// Y: #V x 3 embedding symmetric (exactly or nearly) about the plane x = 0, #V >= 3.
// Returns Y_c = Y R^T + t^T (each row y_c = R y + t) with
//   - the vertex centroid's y and z at the origin (x is left alone so the plane stays x = 0),
//   - the plane normal along +-x (R maps the x axis to +-x),
//   - y = the in-plane principal axis of largest variance, z = the other one,
//   - det R = +1 (a proper rotation: left and right are never swapped).
// The sign of y and of z is chosen so that the third moment of that coordinate is positive
// (the longer tail of the distribution points to +), which is deterministic and consistent for
// isometric shapes in most cases; the remaining ambiguity is the flip stage's job. x then
// follows from y x z. R and t are returned through the pointers when given, and axis_ratio
// = sqrt(variance along z / variance along y) in [0, 1]: near 1, which in-plane axis is y is
// ill-determined, and shapes of one class may disagree on it.
// Throws InvalidInputError for fewer than 3 rows or non-finite coordinates.
Eigen::MatrixX3d CanonicalFrame(const Eigen::MatrixX3d& Y, Eigen::Matrix3d* R = nullptr,
                                Eigen::Vector3d* t = nullptr, double* axis_ratio = nullptr);

}  // namespace symembed

// Shared steps of the symmetrize stages: moving the symmetry plane to x = 0, the asymmetry
// measure, and dense vertices following the samples.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "registry/stages.h"
#include "registry/types.h"

namespace symembed {

// M = diag(-1, 1, 1), the reflection about x = 0.
inline Eigen::Matrix3d MirrorX() { return Eigen::Vector3d(-1.0, 1.0, 1.0).asDiagonal(); }

// Y (#V x 3) moved rigidly so that the plane normal . y = offset becomes x = 0 with the normal
// along +x: y' = Q (y - offset * normal), Q the shortest rotation taking normal to +x.
// Throws InvalidInputError when Y is not 3D or the normal is zero.
Eigen::MatrixX3d MovePlaneToX0(const Eigen::MatrixXd& Y, const Eigen::Vector3d& normal,
                               double offset);

// mean_i ||M p_i - p_sigma(i)|| / size, size = RMS distance of the rows of P (#S x 3) to their
// centroid. 0 for a set exactly symmetric about x = 0 under sigma.
double Asymmetry(const Eigen::MatrixX3d& P, const std::vector<int>& sigma);

// Rows `samples` of Y.
Eigen::MatrixX3d SampleRows3(const Eigen::MatrixX3d& Y, const std::vector<int>& samples);

// Dense vertices follow the samples: each vertex of Y (#V x 3) moves by the inverse-squared-
// distance weighted mean of the displacements P_new - P_old of its k nearest samples (nearest in
// Y, sample positions P_old = rows `samples` of Y); sample vertices move exactly with their
// sample. P_new: #S x 3. Returns #V x 3.
Eigen::MatrixX3d FollowSamples(const Eigen::MatrixX3d& Y, const std::vector<int>& samples,
                               const Eigen::MatrixX3d& P_new, int k);

// Checks the symmetry input (3D embedding, sample ids, sigma of the right size and range).
// Throws InvalidInputError.
void CheckSymmetrizeInput(const SymmetryInput& input, const SymmetryResult& symmetry);

}  // namespace symembed

// Posing a synthetic figure by linear blend skinning [Magnenat-Thalmann et al. 1988].
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "core/mesh.h"
#include "eval/synthetic/rest_shape.h"

namespace symembed {

struct Pose {
  // #bones local rotations in the rest frame (a child's global rotation is its parent's times
  // its own, about its rest joint); rotations[0] (torso) is the identity.
  std::vector<Eigen::Matrix3d> rotations;
  // #bones factors along the bone (length) and across it (thickness); 1 = rest.
  std::vector<double> length_scale, thickness_scale;
};

// The identity pose.
Pose RestPose(int num_bones);

// Joint angles drawn uniformly within each bone's range (right bones get the mirror image
// M R M, M = diag(-1, 1, 1), of a rotation drawn from the left-side range). When
// nonisometric > 0, every bone but the torso also gets length and thickness factors uniform
// in [1 - nonisometric, 1 + nonisometric] (a separate stream, scale_seed). nonisometric < 1.
Pose RandomPose(const std::vector<Bone>& bones, uint32_t angle_seed, double nonisometric,
                uint32_t scale_seed);

// Linear blend skinning: v' = sum_b w_vb (A_b v + t_b) with A_b = R_b S_b, R_b the bone's global
// rotation, S_b its length/thickness scaling about its rest joint, and t_b moving the rest
// joint to its posed position (a child's joint follows its parent's rotation and length).
// Returns #V x 3 posed positions of rest.surface's vertices.
Eigen::MatrixX3d SkinVertices(const RestFigure& rest, const Pose& pose);

}  // namespace symembed

#include "eval/synthetic/posing.h"

#include <Eigen/Geometry>
#include <cmath>

#include "core/errors.h"
#include "eval/synthetic/random.h"

namespace symembed {

Pose RestPose(int num_bones) {
  Pose pose;
  pose.rotations.assign(num_bones, Eigen::Matrix3d::Identity());
  pose.length_scale.assign(num_bones, 1.0);
  pose.thickness_scale.assign(num_bones, 1.0);
  return pose;
}

Pose RandomPose(const std::vector<Bone>& bones, uint32_t angle_seed, double nonisometric,
                uint32_t scale_seed) {
  SYMEMBED_CHECK(nonisometric >= 0.0 && nonisometric < 1.0, "nonisometric must be in [0, 1)");
  const int n = static_cast<int>(bones.size());
  Pose pose = RestPose(n);
  SynthRandom angles(angle_seed);
  const Eigen::Matrix3d M = Eigen::Vector3d(-1, 1, 1).asDiagonal();
  for (int b = 1; b < n; ++b) {
    double a[3];
    for (int k = 0; k < 3; ++k) a[k] = angles.Uniform(bones[b].min_angles[k], bones[b].max_angles[k]);
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(a[2], Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(a[1], Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(a[0], Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    pose.rotations[b] = bones[b].right ? Eigen::Matrix3d(M * R * M) : R;
  }
  if (nonisometric > 0.0) {
    SynthRandom scales(scale_seed);
    for (int b = 1; b < n; ++b) {
      pose.length_scale[b] = scales.Uniform(1.0 - nonisometric, 1.0 + nonisometric);
      pose.thickness_scale[b] = scales.Uniform(1.0 - nonisometric, 1.0 + nonisometric);
    }
  }
  return pose;
}

Eigen::MatrixX3d SkinVertices(const RestFigure& rest, const Pose& pose) {
  const std::vector<Bone>& bones = rest.figure.bones;
  const int nb = static_cast<int>(bones.size());
  SYMEMBED_CHECK(static_cast<int>(pose.rotations.size()) == nb, "pose has the wrong bone count");
  std::vector<Eigen::Matrix3d> global(nb), A(nb);
  std::vector<Eigen::Vector3d> joint(nb), t(nb);
  for (int b = 0; b < nb; ++b) {
    const Bone& bone = bones[b];
    const Eigen::Vector3d axis = (bone.tail - bone.head).normalized();
    const Eigen::Matrix3d S = pose.thickness_scale[b] * Eigen::Matrix3d::Identity() +
                              (pose.length_scale[b] - pose.thickness_scale[b]) * axis * axis.transpose();
    if (bone.parent < 0) {
      global[b] = pose.rotations[b];
      joint[b] = bone.head;
    } else {
      const int p = bone.parent;
      SYMEMBED_CHECK(p < b, "bone parents must precede their children");
      global[b] = global[p] * pose.rotations[b];
      joint[b] = joint[p] + A[p] * (bone.head - bones[p].head);
    }
    A[b] = global[b] * S;
    t[b] = joint[b] - A[b] * bone.head;
  }
  const Eigen::MatrixX3d& V = rest.surface.V;
  Eigen::MatrixX3d out = Eigen::MatrixX3d::Zero(V.rows(), 3);
  for (int i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d v = V.row(i).transpose();
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int b = 0; b < nb; ++b) {
      const double w = rest.weights(i, b);
      if (w != 0.0) p += w * (A[b] * v + t[b]);
    }
    out.row(i) = p.transpose();
  }
  return out;
}

}  // namespace symembed

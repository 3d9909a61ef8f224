// Box models and skeletons of the synthetic figures.
//
// A figure is a coarse quad "box model": a torso box on a 3 x 3 x 3 grid from whose faces the
// limbs are extruded ring by ring (humanoid: head, two arms, two legs; quadruped: head, tail,
// four legs), with y up, z to the front and the bilateral symmetry plane x = 0 (right limbs are
// the mirror images of the left ones). Every control vertex carries linear-blend-skinning
// weights (torso vertices belong to the torso, limb rings blend the bones they join), so that
// subdividing the weights with the same stencils as the points gives smooth skinning weights.
// Units: metres (humanoid about 1.8 tall, quadruped about 0.8 tall and 1.3 long).
#pragma once

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

namespace symembed {

enum class FigureKind { kHumanoid, kQuadruped };

// "humanoid" / "quadruped"; FigureKindFromName throws ConfigError listing the valid names.
std::string FigureKindName(FigureKind kind);
FigureKind FigureKindFromName(const std::string& name);

struct Bone {
  std::string name;      // "upper_arm_l", ...
  int parent = -1;       // -1 for the root (torso)
  int mirror = 0;        // the bone's mirror image (itself for central bones)
  bool right = false;    // a right-side bone: its rotations are mirrored from left-side ranges
  Eigen::Vector3d head = Eigen::Vector3d::Zero();  // rest position of the joint to the parent
  Eigen::Vector3d tail = Eigen::Vector3d::Zero();  // rest position of the bone's far end
  // Rotation ranges in radians about the x, y, z axes of the rest frame, as for a left-side
  // (or central) bone: R = Rz(z) Ry(y) Rx(x) with each angle in [min, max].
  Eigen::Vector3d min_angles = Eigen::Vector3d::Zero();
  Eigen::Vector3d max_angles = Eigen::Vector3d::Zero();
};

struct ControlMesh {
  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 4>> quads;  // counter-clockwise seen from outside
  Eigen::MatrixXd weights;                // #points x #bones, rows sum to 1
};

struct Figure {
  FigureKind kind = FigureKind::kHumanoid;
  ControlMesh control;
  std::vector<Bone> bones;  // bones[0] is the torso (root); parents precede children
  // Bones that `partial` may cut away with everything they carry (hands, feet, head).
  std::vector<int> cuttable;
};

// The box model. rings_per_segment >= 1 splits every interval between the modelled rings into
// that many rings (a finer control mesh, hence more vertices after subdivision).
Figure BuildFigure(FigureKind kind, int rings_per_segment);

// Number of quads of BuildFigure(kind, rings_per_segment).control.
int ControlQuadCount(FigureKind kind, int rings_per_segment);

}  // namespace symembed

// The synthetic reproduction of SHREC'16's cuts for the partial-shape tests: the poses of a
// humanoid class, once whole and once each cut by a random plane (plane_cuts 0.5: some poses
// lose 10-40% of their vertices, the others stay whole), with rest ids as the ground truth.
#pragma once

#include "eval/synthetic/synthetic.h"

namespace symembed::testing {

struct CutAndWholeClasses {
  SynthClass whole, cut;  // shapes[p] of both: pose p
};

inline CutAndWholeClasses CutHumanoidClasses(int vertices) {
  SynthOptions o;
  o.kinds = {FigureKind::kHumanoid};
  o.poses = 6;
  o.vertices = vertices;
  SynthOptions cut_options = o;
  cut_options.plane_cuts = 0.5;
  return {GenerateClass(FigureKind::kHumanoid, o),
          GenerateClass(FigureKind::kHumanoid, cut_options)};
}

}  // namespace symembed::testing

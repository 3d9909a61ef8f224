// The synthetic ground-truth benchmark: posed, optionally remeshed / scaled / noisy / partial
// copies of a bilaterally symmetric articulated figure, written in the pairs_vts layout.
//
// Every shape's vertices are rest vertices (or a subset of them), so the ground truth is
// exact: ground-truth line i of every shape of a class is rest vertex i, and the mirrored
// ground truth of line i is rest vertex mirror[i]. Written layout (DIR):
//   shapes/NAME.off      NAME = kind + pose index (humanoid0, humanoid1, ...; class = kind)
//   corres/NAME.vts      one line per rest vertex i: the 1-based id of rest vertex i in NAME,
//                        or 0 when NAME does not have it (remeshed away or cut off)
//   corres/NAME.sym.vts  the same for rest vertex mirror[i]
//   test_pairs.txt       "A<TAB>B" per line: all unordered pairs within a class in pose order,
//                        or a seeded subset of `pairs` per class (kept in that order); with
//                        cross_class, every pose of a kind onto every pose of its cross class
//                        (or a seeded subset of `pairs` per kind) instead
//   README.md            the generator options and seed, and this description
// The same options give byte-identical files: random numbers come from std::mt19937 through
// platform-independent conversions (random.h), meshes are written by SaveMesh (shortest
// round-trip decimal form, so the written positions are exactly the generated doubles); only
// the trigonometry (the C library's sin/cos) could differ between platforms.
#pragma once

#include <string>
#include <vector>

#include "core/range.h"
#include "eval/synthetic/rest_shape.h"
#include "eval/synthetic/variations.h"

namespace symembed {

struct SynthOptions {
  std::vector<FigureKind> kinds = {FigureKind::kHumanoid};  // one class per kind
  // Shapes per class.
  int poses = 8;
  static constexpr Range kPoses = Range::Closed(1, 10000);
  int vertices = 5000;  // approximate rest vertex count (see ChooseResolution)
  static constexpr Range kVertices = Range::Closed(100, 10000000);
  int seed = 1;
  static constexpr Range kSeed = Range::AtLeast(0);
  // > 0: decimate every pose independently to this many vertices (a target below 50 is
  // degenerate); 0: off.
  int remesh = 0;
  static constexpr Range kRemesh = Range::AtLeast(0);
  // > 1: the remeshing measures edges this many times longer along a random direction per pose
  // (needs remesh > 0).
  double remesh_anisotropy = 1.0;
  static constexpr Range kRemeshAnisotropy = Range::Closed(1.0, 20.0);
  // > 0: per-pose bone length/thickness factors in [1-R, 1+R] (R < 0.5 keeps them positive).
  double nonisometric = 0.0;
  static constexpr Range kNonisometric = Range::ClosedOpen(0.0, 0.5);
  double noise = 0.0;  // > 0: normal noise amplitude as a fraction of the mean edge length
  static constexpr Range kNoise = Range::Closed(0.0, 1.0);
  // The fractions of poses below, partial to glue, are each in kFraction.
  static constexpr Range kFraction = Range::Closed(0.0, 1.0);
  double partial = 0.0;  // fraction of poses with a hand, foot or head cut away
  // Fraction of poses with a part of the surface cut away by a plane, removing a fraction of the
  // vertices uniform in [0.1, 0.4] (SHREC'16 partial "cuts").
  double plane_cuts = 0.0;
  // Fraction of poses with 1 to 3 holes, each of graph radius uniform in [0.03, 0.12] x
  // sqrt(area) around a random vertex (SHREC'16 partial "holes").
  double holes = 0.0;
  // Fraction of poses with topological noise: each is the closest to contact of
  // kContactDraws seeded pose draws (two parts far apart in the skeleton coming closest,
  // GlueGap), pulled into contact there (PullIntoContact) and glued by glue_bridges tubes
  // (GlueParts); glue_bridges = 0 keeps the same contact poses unglued, the control of the
  // same shapes without the noise
  double glue = 0.0;
  int glue_bridges = 8;
  static constexpr Range kGlueBridges = Range::Closed(0, 1000);
  // > 0 gives every kind a second class, KIND_cross, of another body plan on the
  // same mesh (so rest vertex ids still correspond): bone lengths and thicknesses, the torso's
  // included, scaled by class factors uniform in [1 - R, 1 + R] (equal on mirrored bones, so the
  // body stays bilaterally symmetric), and the body bent forwards (z += R/2 (y - y0)^2 / height,
  // y0 the lowest point: a stooped, ape-like stance whose back and front curve unlike the
  // base class's). Pairs then cross classes (see test_pairs.txt).
  double cross_class = 0.0;
  static constexpr Range kCrossClass = Range::ClosedOpen(0.0, 0.5);
  int pairs = 0;  // > 0: pairs per class in test_pairs.txt; 0: all unordered pairs
  static constexpr Range kPairs = Range::AtLeast(0);

  // The options as a dataset's config names them (core/range.h), besides kinds. The failure
  // modes are read only when given, so that the resolved config of a dataset without them stays
  // as it was.
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("poses", self.poses, kPoses);
    visit("vertices", self.vertices, kVertices);
    visit("seed", self.seed, kSeed);
    visit("remesh", self.remesh, kRemesh);
    visit("remesh_anisotropy", self.remesh_anisotropy, kRemeshAnisotropy);
    visit("nonisometric", self.nonisometric, kNonisometric);
    visit("noise", self.noise, kNoise);
    visit("partial", self.partial, kFraction);
    visit("pairs", self.pairs, kPairs);
    visit("plane_cuts", self.plane_cuts, kFraction, kIfGiven);
    visit("holes", self.holes, kFraction, kIfGiven);
    visit("glue", self.glue, kFraction, kIfGiven);
    visit("glue_bridges", self.glue_bridges, kGlueBridges, kIfGiven);
    visit("cross_class", self.cross_class, kCrossClass, kIfGiven);
  }
  bool IsValid(std::string* error) const;
};

// Pose draws per glued pose (SynthOptions::glue).
constexpr int kContactDraws = 24;

struct SynthShape {
  std::string name;
  TrackedSurface shape;  // shape.rest_ids: rest vertex id of every vertex
  std::string note;      // what was done to it ("cut hand_l", ...), for the README
};

struct SynthClass {
  std::string name;  // the kind's name
  RestFigure rest;
  std::vector<SynthShape> shapes;
  std::vector<std::pair<int, int>> pairs;  // indices into shapes
};

// Which body a class has: the kind's own, or the other body plan of SynthOptions::cross_class
// (class KIND_cross; its random streams are its own).
enum class ClassBody { kBase, kCross };

// Generates one class (poses in parallel; the result does not depend on the thread count);
// its pairs are those within the class. Throws ConfigError when options are invalid, or when
// body is kCross and options.cross_class is 0.
SynthClass GenerateClass(FigureKind kind, const SynthOptions& options,
                         ClassBody body = ClassBody::kBase);

// The pairs of test_pairs.txt between a kind's class (first) and its cross class (second): all
// poses.size()^2, or a seeded subset of options.pairs, in order.
std::vector<std::pair<int, int>> CrossClassPairs(FigureKind kind, const SynthOptions& options);

// The generator options as canonical "key: value" lines (README, cache keys).
std::string SynthOptionsText(const SynthOptions& options);

// Writes the dataset for every kind of options.kinds into dir (created; files overwritten).
// Throws IoError when a file cannot be written.
void WriteSyntheticDataset(const std::string& dir, const SynthOptions& options);

}  // namespace symembed

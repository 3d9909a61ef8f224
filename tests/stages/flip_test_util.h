// Inputs shared by the flip tests: shapes with canonical embeddings and samples, the oracle's
// choice on a pair with identity ground truth, synthetic humanoid poses and their bases.
#pragma once

#include <algorithm>
#include <array>
#include <sstream>
#include <string>

#include "core/canonical_frame.h"
#include "core/errors.h"
#include "core/fmap/functional_map.h"
#include "core/primitives.h"
#include "core/spectral.h"
#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"

namespace symembed::testing {

// The `extrinsic` flip stage with the terms of its former default (curvature weight 1, descriptor
// and orientation at the weights given, refined_maps off) and the decision `decide` (a YAML map);
// descriptor_options: further keys of the descriptor term (", axes: 2").
inline std::string FormerTerms(double descriptor, double orientation,
                               const std::string& decide = "{type: refined_front_back}",
                               const std::string& descriptor_options = "") {
  std::ostringstream yaml;
  yaml << "{type: extrinsic, terms: {curvature: {weight: 1}, descriptor: {weight: " << descriptor
       << descriptor_options
       << "}, refined_maps: {weight: 0}, orientation: {weight: " << orientation
       << "}}, decide: " << decide << "}";
  return yaml.str();
}

// The stage's former default: those terms at weight 1 and the refined front-back decision (the
// studies' base flip stage).
inline const std::string kFormerDefault = FormerTerms(1, 1);

inline ShapeData FlipShape(const std::string& name, const Surface& surface) {
  ShapeData shape;
  shape.name = name;
  shape.surface = surface;
  shape.Y = CanonicalFrame(surface.V);
  // Well-spread samples, as the pipeline's farthest-point sampling gives (the orientation term
  // refines and measures on them).
  shape.samples = EuclideanFarthestPoints(surface.V, std::min(300, surface.NumVertices()));
  return shape;
}

inline PreprocessedGroundTruth IdentityGroundTruth(int n) {
  PreprocessedGroundTruth gt;
  for (int i = 0; i < n; ++i) {
    gt.source_ids.push_back(i);
    gt.target_ids.push_back(i);
  }
  return gt;
}

// The candidate of the oracle flip stage for a pair with ground truth `gt`.
inline int OracleChoice(const ShapeData& source, const ShapeData& target,
                        const PreprocessedGroundTruth& gt) {
  Registry registry;
  RegisterBuiltinStages(registry);
  auto oracle = registry.CreateAs<FlipStage>("flip", YAML::Load("{type: oracle}"), "t.yaml", "f");
  return oracle->Run(PairInput{source, target, &gt}).chosen;
}

// The same for a pair on one vertex set (identity ground truth).
inline int OracleChoice(const ShapeData& source, const ShapeData& target) {
  return OracleChoice(source, target, IdentityGroundTruth(source.surface.NumVertices()));
}

// Two poses of a generated figure (connected, one vertex set: identity ground truth);
// `nonisometric` as SynthOptions'.
inline std::array<ShapeData, 2> TwoPoses(FigureKind kind, int vertices, double nonisometric = 0.0) {
  SynthOptions synth;
  synth.poses = 2;
  synth.vertices = vertices;
  synth.nonisometric = nonisometric;
  const SynthClass figures = GenerateClass(kind, synth);
  SYMEMBED_CHECK(figures.shapes.size() == 2u, "the generator made " << figures.shapes.size());
  return {FlipShape("pose0", figures.shapes[0].shape.surface),
          FlipShape("pose1", figures.shapes[1].shape.surface)};
}

// Two poses of the synthetic humanoid.
inline std::array<ShapeData, 2> HumanoidPoses(int vertices) {
  return TwoPoses(FigureKind::kHumanoid, vertices);
}

// The first k Laplace-Beltrami eigenpairs of both shapes.
inline std::array<LaplaceBasis, 2> Bases(const ShapeData& a, const ShapeData& b, int k) {
  LaplaceBasisOptions options;
  options.k = k;
  return {ComputeLaplaceBasis(a.surface, options), ComputeLaplaceBasis(b.surface, options)};
}

}  // namespace symembed::testing

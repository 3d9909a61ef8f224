// The per-shape stages at their built-in defaults, run on one surface as the pipeline runs them
// (sampling, geodesics, embedding, symmetry, symmetrize, canonical frame): for tests of what the
// defaults give on generated shapes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/canonical_frame.h"
#include "eval/synthetic/synthetic.h"
#include "registry/registry.h"

namespace symembed::testing {

template <typename T>
std::unique_ptr<T> MakeStageAs(const Registry& r, const std::string& kind,
                               const std::string& yaml) {
  return r.CreateAs<T>(kind, YAML::Load(yaml), "test.yaml", "pipeline." + kind);
}

// ShapeData of `surface` (name, samples, embedding, symmetry, canonical Y) with every stage at
// its defaults but the symmetry stage, given by its YAML. Throws what a stage throws.
inline ShapeData RunDefaultShapeStages(const std::string& name, const Surface& surface,
                                       const std::string& symmetry = "{type: plane2d}",
                                       const std::string& symmetrize = "{type: ceres}") {
  Registry r;
  RegisterBuiltinStages(r);
  ShapeData shape;
  shape.name = name;
  shape.surface = surface;
  shape.samples = MakeStageAs<SamplingStage>(r, "sampling", "{type: farthest_point}")
                      ->Run(surface)
                      .samples;
  const Eigen::MatrixXd D = MakeStageAs<GeodesicsStage>(r, "geodesics", "{type: dijkstra}")
                                ->Prepare(surface)
                                ->Distances(shape.samples);
  shape.embedding = MakeStageAs<EmbeddingStage>(r, "embedding", "{type: lsmds}")
                        ->Run(EmbeddingInput{surface, shape.samples, D});
  const SymmetryInput input{surface, shape.samples, D, shape.embedding};
  shape.symmetry = MakeStageAs<SymmetryStage>(r, "symmetry", symmetry)->Run(input);
  shape.Y = CanonicalFrame(
      MakeStageAs<SymmetrizeStage>(r, "symmetrize", symmetrize)->Run(input, shape.symmetry).Y);
  return shape;
}

// The vertex id of each rest vertex in a generated shape (-1 where it was cut away).
inline std::vector<int> VertexOfRest(const TrackedSurface& shape, int rest_vertices) {
  std::vector<int> of_rest(rest_vertices, -1);
  for (size_t v = 0; v < shape.rest_ids.size(); ++v) of_rest[shape.rest_ids[v]] = static_cast<int>(v);
  return of_rest;
}

// The ground truth from a to b, two generated shapes of a class of rest_vertices vertices: the
// rest vertices both kept.
inline PreprocessedGroundTruth RestGroundTruth(const TrackedSurface& a, const TrackedSurface& b,
                                               int rest_vertices) {
  const std::vector<int> of_rest = VertexOfRest(b, rest_vertices);
  PreprocessedGroundTruth gt;
  for (size_t v = 0; v < a.rest_ids.size(); ++v) {
    if (of_rest[a.rest_ids[v]] < 0) continue;
    gt.source_ids.push_back(static_cast<int>(v));
    gt.target_ids.push_back(of_rest[a.rest_ids[v]]);
  }
  return gt;
}

}  // namespace symembed::testing

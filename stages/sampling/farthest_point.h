// Geodesic farthest point sampling (`farthest_point`) and the trivial `all` sampling.
//
// FPS starts from a vertex drawn with the seed, then repeatedly adds the vertex farthest (in
// edge-graph distance, core/mesh_graph.h) from every sample so far. The nearest-sample distance
// of every vertex is kept up to date incrementally: each new sample runs a Dijkstra search that
// only expands where it lowers that distance, so the total cost is far below #S full searches.
// The samples of a smaller count are a prefix of those of a larger one (same seed).
//
// [Eldar et al. 1997] The farthest point strategy for progressive image sampling;
// [Moenning & Dodgson 2003] Fast marching farthest point sampling.
#pragma once

#include <cstdint>
#include <string>

#include "core/mesh.h"
#include "core/range.h"
#include "registry/types.h"

namespace symembed {

struct FarthestPointOptions {
  int count = 1000;        // number of samples; clamped to the number of usable vertices
  static constexpr Range kCount = Range::AtLeast(1);
  std::uint32_t seed = 1;  // seeds the choice of the first sample

  // The options as the config names them (core/range.h).
  template <typename Self, typename Visit>
  static void Fields(Self& self, Visit&& visit) {
    visit("count", self.count, kCount);
    visit("seed", self.seed, Range::AtLeast(0));
  }
  bool IsValid(std::string* error) const { return NoViolation(FieldViolation(*this), error); }
};

// Returns `count` distinct vertex ids in sampling order and the coverage radius (the largest
// graph distance from a vertex to its nearest sample; +infinity if some component has no
// sample). Vertices in no face are never sampled. status.message says when count was clamped.
// Throws InvalidInputError when the surface has no faces.
SamplingResult FarthestPointSampling(const Surface& surface,
                                     const FarthestPointOptions& options = {});

// Every vertex, in id order; coverage radius 0.
SamplingResult AllVerticesSampling(const Surface& surface);

}  // namespace symembed

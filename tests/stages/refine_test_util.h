// A pair of shapes with a known ground truth and the error measure the refine tests use: a
// bumpy blob and a twisted, shuffled copy, or two poses of the synthetic humanoid; and the ground
// truth perturbed locally, as a start for refinement.
#pragma once

#include <cmath>
#include <random>
#include <set>
#include <vector>

#include "eval/synthetic/synthetic.h"
#include "registry/types.h"
#include "tests/test_util.h"

namespace symembed::testing {

struct Pair {
  ShapeData source, target;
  std::vector<int> truth;  // source vertex -> target vertex
};

inline Pair MakePair(int n, double twist) {
  Pair p;
  p.source.name = "blob";
  p.source.surface = testing::BumpyBlob(n, 3);
  p.target.name = "twisted";
  p.target.surface = testing::TwistedShuffledCopy(p.source.surface, twist, 5, &p.truth);
  return p;
}

// Mean Euclidean distance on the target between mapped and true vertices / sqrt(area): the
// benchmark's error measure with Euclidean for geodesic distance (equal at these small errors).
inline double MeanError(const Pair& p, const std::vector<int>& map) {
  const Surface& t = p.target.surface;
  double sum = 0.0;
  for (size_t i = 0; i < map.size(); ++i) sum += (t.V.row(map[i]) - t.V.row(p.truth[i])).norm();
  return sum / map.size() / std::sqrt(TotalArea(t));
}

// The ground truth with `fraction` of its entries replaced by a random target vertex within
// `rings` edge rings of the true one (seeded).
inline std::vector<int> PerturbedTruth(const Pair& p, double fraction, int rings, unsigned seed) {
  const Surface& t = p.target.surface;
  std::vector<std::set<int>> adjacent(t.NumVertices());
  for (int f = 0; f < t.NumFaces(); ++f) {
    for (int k = 0; k < 3; ++k) adjacent[t.F(f, k)].insert(t.F(f, (k + 1) % 3));
    for (int k = 0; k < 3; ++k) adjacent[t.F(f, (k + 1) % 3)].insert(t.F(f, k));
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  std::vector<int> map = p.truth;
  for (int& m : map) {
    if (uniform(rng) >= fraction) continue;
    std::set<int> ball = {m}, frontier = {m};
    for (int r = 0; r < rings; ++r) {
      std::set<int> next;
      for (int v : frontier) {
        for (int w : adjacent[v]) {
          if (ball.insert(w).second) next.insert(w);
        }
      }
      frontier = next;
    }
    ball.erase(m);
    std::vector<int> choices(ball.begin(), ball.end());
    m = choices[std::uniform_int_distribution<int>(0, choices.size() - 1)(rng)];
  }
  return map;
}

// Two poses (0 and 1) of the synthetic humanoid (eval/synthetic) with about 2,000 vertices; the
// identity of rest ids is the ground truth, and *mirrored (optional) the truth composed with the
// rest mirror (the flipped map). nonisometric: the generator's per-pose bone stretch (0: none).
inline Pair PosedHumanoidPair(double nonisometric, std::vector<int>* mirrored = nullptr) {
  SynthOptions options;
  options.poses = 2;
  options.vertices = 2000;
  options.nonisometric = nonisometric;
  const SynthClass cls = GenerateClass(FigureKind::kHumanoid, options);
  Pair p;
  p.source.surface = cls.shapes[0].shape.surface;
  p.target.surface = cls.shapes[1].shape.surface;
  std::vector<int> target_of_rest(cls.rest.surface.NumVertices(), -1);
  const auto& target_rest = cls.shapes[1].shape.rest_ids;
  for (size_t j = 0; j < target_rest.size(); ++j) target_of_rest[target_rest[j]] = j;
  const auto& source_rest = cls.shapes[0].shape.rest_ids;
  p.truth.resize(source_rest.size());
  if (mirrored != nullptr) mirrored->resize(source_rest.size());
  for (size_t i = 0; i < source_rest.size(); ++i) {
    p.truth[i] = target_of_rest[source_rest[i]];
    if (mirrored != nullptr) (*mirrored)[i] = target_of_rest[cls.rest.mirror[source_rest[i]]];
  }
  return p;
}

}  // namespace symembed::testing

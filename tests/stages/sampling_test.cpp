#include <gtest/gtest.h>

#include <set>

#include "core/mesh_graph.h"
#include "core/primitives.h"
#include "registry/registry.h"
#include "stages/sampling/farthest_point.h"

namespace symembed {
namespace {

TEST(FarthestPointSampling, DistinctDeterministicAndPrefixConsistent) {
  const Surface sphere = Icosphere(3);
  const SamplingResult a = FarthestPointSampling(sphere, {50, 3});
  const SamplingResult b = FarthestPointSampling(sphere, {50, 3});
  const SamplingResult small = FarthestPointSampling(sphere, {10, 3});
  EXPECT_EQ(a.samples, b.samples);
  EXPECT_EQ(std::set<int>(a.samples.begin(), a.samples.end()).size(), 50u);
  EXPECT_TRUE(std::equal(small.samples.begin(), small.samples.end(), a.samples.begin()));
  EXPECT_NE(FarthestPointSampling(sphere, {50, 4}).samples[0], a.samples[0]);
}

TEST(FarthestPointSampling, CoverageRadiusIsExactAndDecreasesWithCount) {
  const Surface grid = GridMesh(30, 20, 3.0, 2.0);
  const MeshGraph graph = BuildMeshGraph(grid);
  double previous = std::numeric_limits<double>::infinity();
  for (int count : {1, 2, 5, 10, 20, 50, 100, 200}) {
    const SamplingResult r = FarthestPointSampling(grid, {count, 1});
    ASSERT_EQ(static_cast<int>(r.samples.size()), count);
    EXPECT_LE(r.coverage_radius, previous);
    previous = r.coverage_radius;
    // Coverage radius = max over vertices of the distance to the nearest sample.
    std::vector<double> nearest(grid.NumVertices(), std::numeric_limits<double>::infinity());
    std::vector<double> d(grid.NumVertices());
    DijkstraWorkspace<double> ws;
    for (int s : r.samples) {
      Dijkstra<double>(graph, s, d.data(), &ws);
      for (int v = 0; v < grid.NumVertices(); ++v) nearest[v] = std::min(nearest[v], d[v]);
    }
    EXPECT_NEAR(r.coverage_radius, *std::max_element(nearest.begin(), nearest.end()), 1e-12);
  }
  // 200 samples on a 3 x 2 rectangle (area 6): a covering disc per sample has area ~ 6 / 200.
  EXPECT_LT(previous, 0.25);
}

TEST(FarthestPointSampling, ClampsCountAndSkipsIsolatedVertices) {
  Surface s = GridMesh(3, 3);
  s.V.conservativeResize(10, 3);
  s.V.row(9) << 5, 5, 5;  // in no face
  const SamplingResult r = FarthestPointSampling(s, {100, 1});
  EXPECT_EQ(r.samples.size(), 9u);
  EXPECT_EQ(std::count(r.samples.begin(), r.samples.end(), 9), 0);
  EXPECT_FALSE(r.status.message.empty());
  EXPECT_THROW(FarthestPointSampling(s, {0, 1}), ConfigError);
}

TEST(AllSampling, EveryVertex) {
  const Surface sphere = Icosphere(1);
  Registry registry;
  RegisterBuiltinStages(registry);
  auto stage = registry.CreateAs<SamplingStage>("sampling", YAML::Load("{type: all}"), "t.yaml",
                                                "pipeline.sampling");
  const SamplingResult r = stage->Run(sphere);
  ASSERT_EQ(static_cast<int>(r.samples.size()), sphere.NumVertices());
  for (int i = 0; i < sphere.NumVertices(); ++i) EXPECT_EQ(r.samples[i], i);
  EXPECT_EQ(r.coverage_radius, 0.0);
}

TEST(FarthestPointSampling, RegisteredWithStrictOptions) {
  Registry registry;
  RegisterBuiltinStages(registry);
  auto stage = registry.CreateAs<SamplingStage>(
      "sampling", YAML::Load("{type: farthest_point, count: 7, seed: 2}"), "t.yaml",
      "pipeline.sampling");
  EXPECT_EQ(stage->Run(Icosphere(2)).samples.size(), 7u);
  EXPECT_THROW(registry.Create("sampling", YAML::Load("{type: farthest_point, count: 0}"),
                               "t.yaml", "pipeline.sampling"),
               ConfigError);
  EXPECT_THROW(registry.Create("sampling", YAML::Load("{type: farthest_point, samples: 3}"),
                               "t.yaml", "pipeline.sampling"),
               ConfigError);
}

}  // namespace
}  // namespace symembed

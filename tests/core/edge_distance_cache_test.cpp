#include "core/edge_distance_cache.h"

#include <gtest/gtest.h>

#include "core/primitives.h"

namespace symembed {
namespace {

TEST(EdgeDistanceCache, RowsAreThoseOfDijkstraWhetherKeptOrComputed) {
  const Surface sphere = Icosphere(2);
  const MeshGraph graph = BuildMeshGraph(sphere);
  EdgeDistanceCache cache(size_t{1} << 30);
  const std::vector<int> first = {0, 5, 9}, second = {9, 3, 0, 3};
  const Eigen::MatrixXd a = cache.Rows(7, graph, first);
  EXPECT_EQ(a, EdgeGraphDistances(graph, first, 1));
  const size_t kept = cache.Bytes();
  EXPECT_EQ(kept, 3 * sphere.NumVertices() * sizeof(double));
  // Two rows kept, one (3) computed once though asked twice.
  const Eigen::MatrixXd b = cache.Rows(7, graph, second);
  EXPECT_EQ(b, EdgeGraphDistances(graph, second, 1));
  EXPECT_EQ(cache.Bytes(), kept + sphere.NumVertices() * sizeof(double));
}

TEST(EdgeDistanceCache, SurfacesOfOtherKeysShareNoRow) {
  const Surface small = Icosphere(1), large = Icosphere(2);
  const MeshGraph gs = BuildMeshGraph(small), gl = BuildMeshGraph(large);
  EdgeDistanceCache cache(size_t{1} << 30);
  cache.Rows(1, gs, {0, 1});
  EXPECT_EQ(cache.Rows(2, gl, {0, 1}), EdgeGraphDistances(gl, {0, 1}, 1));
  EXPECT_EQ(cache.Rows(1, gs, {1, 0}), EdgeGraphDistances(gs, {1, 0}, 1));
}

TEST(EdgeDistanceCache, DropsTheLeastRecentlyUsedRowsBeyondItsBytes) {
  const Surface sphere = Icosphere(2);
  const MeshGraph graph = BuildMeshGraph(sphere);
  const size_t row = sphere.NumVertices() * sizeof(double);
  EdgeDistanceCache cache(2 * row);
  cache.Rows(1, graph, {0, 1});
  cache.Rows(1, graph, {0});     // 0 used last
  cache.Rows(1, graph, {2});     // drops 1
  EXPECT_EQ(cache.Bytes(), 2 * row);
  EXPECT_EQ(cache.Rows(1, graph, {0, 2, 1}), EdgeGraphDistances(graph, {0, 2, 1}, 1));
  EXPECT_LE(cache.Bytes(), 2 * row);
  // A cache too small for one row keeps none and still answers.
  EdgeDistanceCache none(row - 1);
  EXPECT_EQ(none.Rows(1, graph, {4}), EdgeGraphDistances(graph, {4}, 1));
  EXPECT_EQ(none.Bytes(), 0u);
}

}  // namespace
}  // namespace symembed

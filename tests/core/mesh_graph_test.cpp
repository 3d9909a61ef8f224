#include "core/mesh_graph.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "core/errors.h"
#include "core/primitives.h"
#include "tests/test_util.h"

namespace symembed {
namespace {

// The mesh with its vertices moved at random by up to `jitter` of the mean edge length, so that
// edge lengths spread.
Surface Jittered(Surface s, double jitter, unsigned seed) {
  const MeshGraph g = BuildMeshGraph(s);
  double mean = 0.0;
  for (double l : g.lengths) mean += l;
  mean /= static_cast<double>(g.lengths.size());
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int v = 0; v < s.NumVertices(); ++v) {
    for (int c = 0; c < 3; ++c) s.V(v, c) += jitter * mean * uniform(rng);
  }
  return s;
}

// From every source (every `stride`-th vertex): the bucket queue's values equal the binary
// heap's bit for bit, and each is the floating-point fixed point min_u fl(d(u) + l(u, v)).
template <typename Scalar>
void ExpectBucketsMatchTheHeap(const Surface& s, int stride) {
  const MeshGraph g = BuildMeshGraph(s);
  const int n = g.NumVertices();
  DijkstraWorkspace<Scalar> ws, heap_ws;
  std::vector<Scalar> d(n), h(n);
  for (int source = 0; source < n; source += stride) {
    Dijkstra<Scalar>(g, source, d.data(), &ws);
    DijkstraWithHeap<Scalar>(g, source, h.data(), &heap_ws);
    ASSERT_EQ(d, h) << "source " << source;
    for (int v = 0; v < n; ++v) {
      if (v == source) continue;
      Scalar best = std::numeric_limits<Scalar>::infinity();
      for (int k = g.offsets[v]; k < g.offsets[v + 1]; ++k) {
        best = std::min(best, static_cast<Scalar>(d[g.neighbors[k]] +
                                                  static_cast<Scalar>(g.lengths[k])));
      }
      ASSERT_EQ(d[v], best) << "source " << source << " vertex " << v;
    }
  }
}

TEST(MeshGraph, EachEdgeOnceInEachDirectionOrderedByItsEnds) {
  // A sphere whose faces come in shuffled order, with a face repeated, one reversed and one
  // degenerate (two equal corners): the graph is the set of distinct directed edges between
  // different vertices, ordered by (from, to), each with its Euclidean length.
  Surface s = Icosphere(2);
  std::mt19937 rng(4);
  std::vector<int> order(s.F.rows());
  for (size_t f = 0; f < order.size(); ++f) order[f] = static_cast<int>(f);
  std::shuffle(order.begin(), order.end(), rng);
  Eigen::MatrixXi F(s.F.rows() + 3, 3);
  for (size_t f = 0; f < order.size(); ++f) F.row(f) = s.F.row(order[f]);
  F.row(order.size()) = s.F.row(7);
  F.row(order.size() + 1) << s.F(9, 2), s.F(9, 1), s.F(9, 0);
  F.row(order.size() + 2) << s.F(3, 0), s.F(3, 0), s.F(3, 1);
  s.F = F;
  std::vector<std::pair<int, int>> edges;
  for (int f = 0; f < s.F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = s.F(f, k), b = s.F(f, (k + 1) % 3);
      if (a == b) continue;
      edges.emplace_back(a, b);
      edges.emplace_back(b, a);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  const MeshGraph g = BuildMeshGraph(s);
  ASSERT_EQ(g.NumVertices(), s.NumVertices());
  ASSERT_EQ(g.neighbors.size(), edges.size());
  ASSERT_EQ(g.lengths.size(), edges.size());
  for (size_t e = 0; e < edges.size(); ++e) {
    const auto [a, b] = edges[e];
    EXPECT_GE(static_cast<int>(e), g.offsets[a]);
    EXPECT_LT(static_cast<int>(e), g.offsets[a + 1]);
    EXPECT_EQ(g.neighbors[e], b);
    EXPECT_EQ(g.lengths[e], (s.V.row(a) - s.V.row(b)).norm());
  }
}

TEST(Dijkstra, BucketQueueGivesTheHeapsValuesBitForBit) {
  // Irregular (a blob, and the same with its edges spread by jitter), exactly mirror-symmetric
  // (many paths of equal length), and a regular grid (many equal edge lengths).
  const Surface blob = testing::BumpyBlob(12);
  for (const Surface& s : {blob, Jittered(blob, 0.3, 1), testing::SymmetricFigure(1),
                           GridMesh(25, 20, 3.0, 2.0)}) {
    ExpectBucketsMatchTheHeap<double>(s, 7);
    ExpectBucketsMatchTheHeap<float>(s, 7);
  }
}

TEST(Dijkstra, EdgesOfVeryDifferentLengthsOrOfLengthZero) {
  // An edge a million times shorter than the others, and two vertices at the same place (an edge
  // of length 0): the heap orders the vertices there, with the same result.
  Surface s = GridMesh(12, 10, 3.0, 2.0);
  Surface tiny = s;
  tiny.V.row(1) = tiny.V.row(0) + 1e-6 * (s.V.row(1) - s.V.row(0));
  Surface zero = s;
  zero.V.row(1) = zero.V.row(0);
  for (const Surface& t : {tiny, zero}) {
    const MeshGraph g = BuildMeshGraph(t);
    EXPECT_GT(g.max_length, 1000.0 * g.min_length);
    ExpectBucketsMatchTheHeap<double>(t, 1);
  }
  // Unreachable vertices stay at infinity: a second grid beside the first, not connected.
  Surface two = s;
  two.V.conservativeResize(2 * s.NumVertices(), 3);
  two.V.bottomRows(s.NumVertices()) = s.V.rowwise() + Eigen::RowVector3d(10.0, 0.0, 0.0);
  two.F.conservativeResize(2 * s.F.rows(), 3);
  two.F.bottomRows(s.F.rows()) = s.F.array() + s.NumVertices();
  const MeshGraph g = BuildMeshGraph(two);
  std::vector<double> d(two.NumVertices());
  DijkstraWorkspace<double> ws;
  Dijkstra<double>(g, 3, d.data(), &ws);
  for (int v = s.NumVertices(); v < two.NumVertices(); ++v) {
    EXPECT_EQ(d[v], std::numeric_limits<double>::infinity());
  }
  ExpectBucketsMatchTheHeap<double>(two, 5);
}

// Each vertex takes the seed nearest along the edges (a seed listed twice counts once, as the
// first), a vertex on no edge none; a seed id out of range is refused.
TEST(MeshGraph, NearestSeedsLabelsEachVertexByItsNearestSeedAlongTheEdges) {
  Surface grid = GridMesh(5, 4);  // vertex v at column v % 5, row v / 5
  grid.V.conservativeResize(21, 3);
  grid.V.row(20) = grid.V.row(4);  // on no face
  const MeshGraph graph = BuildMeshGraph(grid);
  const std::vector<int> seed = NearestSeeds(graph, {0, 19, 0});
  ASSERT_EQ(seed.size(), 21u);
  EXPECT_EQ(seed[0], 0);
  EXPECT_EQ(seed[19], 1);
  EXPECT_EQ(seed[1], 0);
  EXPECT_EQ(seed[5], 0);
  EXPECT_EQ(seed[18], 1);
  EXPECT_EQ(seed[14], 1);
  EXPECT_EQ(seed[20], -1);
  for (int v : seed) EXPECT_NE(v, 2);
  EXPECT_THROW(NearestSeeds(graph, {0, 21}), InvalidInputError);
}

}  // namespace
}  // namespace symembed

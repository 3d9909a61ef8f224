// Exact nearest neighbours in a few dimensions: a kd-tree specialised to one neighbour and a
// dimension fixed at compile time (1 to kMaxNearestKdDims).
//
// KnnIndex::Nearest runs it for the searches of the pipeline: the 2D embeddings of the symmetry
// planes' reflection scoring, the 3D embeddings (symmetry in 3D, symmetrization, the flip
// scorers' candidate maps, matching on positions) and the embedded points with normals (6D) of
// matching and of the refined flip term. The tree splits each cell at the median of its widest
// coordinate, keeps up to 16 points per leaf, their coordinates contiguous coordinate by
// coordinate (measured four at a time with AVX2), and prunes with the incremental distance to a
// cell [Arya & Mount 1993, Algorithms for fast vector quantization]: the squared distance from
// the query to the box of splits taken so far, updated one coordinate per level.
//
// A squared distance is the sum of (p_c - q_c)^2 in coordinate order. Up to 7 coordinates that is
// the order of FLANN's L2 distance too (which adds coordinates four at a time to a running sum
// that starts at 0), so the distances are the ones FLANN's kd-tree returns, bit for bit, and so
// are the nearest points wherever the nearest point is unique. Equally near points go to the
// lowest index.
#pragma once

#include <memory>
#include <vector>

#include "core/fmap/nearest_kernel.h"

namespace symembed {

constexpr int kMaxNearestKdDims = 7;

// The search, whatever the dimension.
class NearestSearch {
 public:
  virtual ~NearestSearch() = default;
  virtual int dims() const = 0;

  // The index of the point nearest to q (dims() coordinates), the lowest index among equally near
  // ones; its squared distance through *sq_dist. hint (optional): a point index, measured first;
  // a hint near q (the answer of a neighbouring query) prunes more cells. The answer does not
  // depend on it.
  virtual int Nearest(const double* q, double* sq_dist, int hint = -1) const = 0;
};

template <int D>
class NearestKd final : public NearestSearch {
  static_assert(D >= 1 && D <= kMaxNearestKdDims, "NearestKd: 1 to kMaxNearestKdDims dimensions");

 public:
  // points: n x D, row-major (point i's coordinates at points[i * D ...]), copied. isa: the
  // leaves' scan, AVX2 (kAvx2 or kAvx512; kAuto where NearestKernelSupports it) or the x86-64
  // baseline one point at a time, the same operations, so the same answers and distances bit
  // for bit. Throws InvalidInputError for n < 1 or a non-finite coordinate, InternalError for an
  // isa this processor lacks.
  NearestKd(const double* points, int n, NearestIsa isa = NearestIsa::kAuto);

  int dims() const override { return D; }
  int Nearest(const double* q, double* sq_dist, int hint = -1) const override;

 private:
  struct Node {
    double split = 0.0;
    int dim = -1;               // -1: a leaf holding slots [begin, end)
    int left = -1, right = -1;  // children (inner nodes)
    int begin = 0, end = 0;
    int leaf = -1;  // a leaf's number in leaf_coords_ / leaf_ids_
  };
  int Build(const double* points, int begin, int end);
  void Search(int node, const double* q, double off[D], double bound, double* best,
              int* best_id) const;
  double SquaredDistance(int slot, const double* q) const;

  std::vector<Node> nodes_;
  std::vector<int> ids_;         // point index of each slot, in tree order
  std::vector<int> slots_;       // slot of each point index
  std::vector<double> coords_;   // slot-major: slot s's coordinates at coords_[s * D ...]
  // Per leaf, its points' coordinates as D rows of 16 (leaf_coords_[(leaf * D + c) * 16 + k])
  // and their ids (leaf_ids_[leaf * 16 + k]), padded with points at +infinity and id INT_MAX.
  std::vector<double> leaf_coords_;
  std::vector<int> leaf_ids_;
  bool avx2_ = false;
};

// The tree for `dims` (1 to kMaxNearestKdDims) coordinates per point; points as for NearestKd.
std::unique_ptr<NearestSearch> MakeNearestSearch(const double* points, int n, int dims,
                                                 NearestIsa isa = NearestIsa::kAuto);

}  // namespace symembed

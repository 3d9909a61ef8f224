// Exact nearest neighbours in a few dimensions: a kd-tree specialised to one neighbour and a
// dimension fixed at compile time (1 to kMaxNearestKdDims).
//
// KnnIndex::Nearest runs it for the searches of the pipeline: the 2D embeddings of the symmetry
// planes' reflection scoring, the 3D embeddings (symmetry in 3D, symmetrization, the flip
// scorers' candidate maps, matching on positions) and the embedded points with normals (6D) of
// matching and of the refined flip term. The tree splits each cell at the median of its widest
// coordinate, keeps 8 points per leaf with their coordinates contiguous, and prunes with the
// incremental distance to a cell [Arya & Mount 1993, Algorithms for fast vector quantization]:
// the squared distance from the query to the box of splits taken so far, updated one coordinate
// per level.
//
// A squared distance is the sum of (p_c - q_c)^2 in coordinate order. Up to 7 coordinates that is
// the order of FLANN's L2 distance too (which adds coordinates four at a time to a running sum
// that starts at 0), so the distances are the ones FLANN's kd-tree returns, bit for bit, and so
// are the nearest points wherever the nearest point is unique. Equally near points go to the
// lowest index.
#pragma once

#include <memory>
#include <vector>

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
  // points: n x D, row-major (point i's coordinates at points[i * D ...]), copied. Throws
  // InvalidInputError for n < 1 or a non-finite coordinate.
  NearestKd(const double* points, int n);

  int dims() const override { return D; }
  int Nearest(const double* q, double* sq_dist, int hint = -1) const override;

 private:
  struct Node {
    double split = 0.0;
    int dim = -1;               // -1: a leaf holding slots [begin, end)
    int left = -1, right = -1;  // children (inner nodes)
    int begin = 0, end = 0;
  };
  int Build(const double* points, int begin, int end);
  void Search(int node, const double* q, double off[D], double bound, double* best,
              int* best_id) const;
  double SquaredDistance(int slot, const double* q) const;

  std::vector<Node> nodes_;
  std::vector<int> ids_;         // point index of each slot, in tree order
  std::vector<int> slots_;       // slot of each point index
  std::vector<double> coords_;   // slot-major: slot s's coordinates at coords_[s * D ...]
};

// The tree for `dims` (1 to kMaxNearestKdDims) coordinates per point; points as for NearestKd.
std::unique_ptr<NearestSearch> MakeNearestSearch(const double* points, int n, int dims);

}  // namespace symembed

// Exact nearest neighbours in 3D: a kd-tree specialised to three coordinates and one neighbour.
//
// The flip scorers query every source vertex, turned by each of four candidate rotations, among
// the target's vertices; on a turned candidate the queries lie away from the target surface and
// a search visits many cells. The tree splits each cell at the median of its widest coordinate,
// keeps 8 points per leaf in coordinate arrays, and prunes with the incremental distance to a
// cell [Arya & Mount 1993, Algorithms for fast vector quantization]: the squared distance from
// the query to the box of splits taken so far, updated one coordinate per level.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace symembed {

class Nearest3d {
 public:
  // points: #N x 3 (#N >= 1, finite), copied. Throws InvalidInputError otherwise.
  explicit Nearest3d(const Eigen::MatrixX3d& points);

  // The index of the point nearest to q (the lowest index among equally near ones); its
  // squared distance through *sq_dist. KnnIndex::Nearest runs it over a matrix of queries.
  // hint (optional): a point index, measured first; a hint near q (the answer of a neighbouring
  // query) prunes more cells. The answer does not depend on it.
  int Nearest(const double q[3], double* sq_dist, int hint = -1) const;

 private:
  struct Node {
    double split = 0.0;
    int dim = -1;               // -1: a leaf holding points [begin, end)
    int left = -1, right = -1;  // children (inner nodes)
    int begin = 0, end = 0;
  };
  int Build(int begin, int end);
  void Search(int node, const double q[3], double off[3], double bound, double* best,
              int* best_id) const;

  std::vector<Node> nodes_;
  std::vector<int> ids_;           // point index of each slot, in tree order
  std::vector<int> slots_;         // slot of each point index
  std::vector<double> x_, y_, z_;  // coordinates in tree order
};

}  // namespace symembed

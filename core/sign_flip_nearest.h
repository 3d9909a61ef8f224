// Nearest neighbours of a point set under every sign flip of its coordinates: for each sign
// pattern s = 1 .. 2^K - 1 (bit j set: coordinate j negated) and each row g_i of G (#N x K), the
// row of G nearest to s(g_i), g_i with those coordinates negated, in Euclidean distance. The
// sign-flip self maps of the spectral symmetry search (stages/symmetry/spectral_symmetry.h).
//
// For one row, ||s(g_i) - g_j||^2 = ||g_i||^2 + c_j(s) with c_j(s) = ||g_j||^2 - 2 s(g_i) . g_j.
// The patterns are visited in Gray-code order, each differing from the one before in a single
// coordinate d, so c_j changes by one multiply-add per row j (4 g_id g_jd times the sign d had).
// Those values pick out the nearest row with a margin far above their rounding: where one row
// alone lies within the margin of the lowest, it is the nearest, and its distance is then
// computed as KnnIndex computes it; where several do, KnnIndex answers that query. So every row
// and distance is KnnIndex::Nearest's for the flipped query, bit for bit. The sweep over the rows
// is compiled for AVX-512, AVX2 and the x86-64 baseline, the widest the processor runs chosen at
// run time, as core/fmap/nearest_kernel.h's kernel.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "core/fmap/nearest_kernel.h"
#include "core/knn.h"

namespace symembed {

struct SignFlipNeighbours {
  int rows = 0;                   // #N
  int patterns = 0;               // 2^K - 1
  std::vector<int> nearest;       // patterns x rows: [(s - 1) * rows + i], a row of G
  std::vector<double> distances;  // the same layout: the Euclidean distance to it
};

// G: #N x K (1 <= K <= 12), finite; index: a KnnIndex built on G (the same rows). The rows are
// split over `threads` threads (0: all cores); the result does not depend on them. `isa` forces
// one build of the sweep (one the processor does not run is a programming error). Throws
// InvalidInputError when index does not match G or K is out of range.
SignFlipNeighbours NearestUnderSignFlips(const Eigen::MatrixXd& G, const KnnIndex& index,
                                         int threads = 1, NearestIsa isa = NearestIsa::kAuto);

}  // namespace symembed

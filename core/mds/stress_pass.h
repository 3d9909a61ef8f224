// The O(n^2) pass of SMACOF (core/mds/smacof.h): the stress of a configuration and the product
// B(X) X of the Guttman transform, in one pass over the unordered pairs.
//
// For D (n x n symmetric dissimilarities), optional weights W (n x n, null for uniform) and X
// (n x dims), returns sigma(X) = sum_{i<j} w_ij (d_ij - ||x_i - x_j||)^2 and, when BX is not
// null, sets BX (n x dims) to B(X) X with b_ij = -w_ij d_ij / ||x_i - x_j|| (0 for coincident
// points), b_ii = -sum_j b_ij, i.e. (B(X) X)_i = sum_j w_ij d_ij / ||x_i - x_j|| (x_i - x_j).
//
// The pairs are split over a fixed number of lanes, each with its own accumulators, so the
// result does not depend on the thread count. Each row i of a lane is computed by a kernel
// compiled twice: with Eigen's expressions for the x86-64 baseline (SSE2), and, for 1 to 4
// dimensions, with AVX2 instructions in one pass that repeats the baseline's arithmetic
// operation for operation (its sums in the order of Eigen 3.4's SSE2 reductions, no fused
// multiply-adds), so both give the same bits. The widest the processor supports is chosen at
// run time.
#pragma once

#include <Eigen/Core>

#include "core/fmap/nearest_kernel.h"

namespace symembed {

// threads: 0 for DefaultThreadCount(). `isa` (the kernels' builds, core/fmap/nearest_kernel.h)
// forces one build of the row kernel: kBaseline the baseline, kAvx2 or kAvx512 the AVX2 build
// (for 1 to 4 dimensions; the baseline for the others); one the processor does not run
// (NearestKernelSupports) throws InternalError. Every build gives the same result bit for bit.
double StressPass(const Eigen::MatrixXd& D, const Eigen::MatrixXd* W, const Eigen::MatrixXd& X,
                  Eigen::MatrixXd* BX, int threads, NearestIsa isa = NearestIsa::kAuto);

}  // namespace symembed

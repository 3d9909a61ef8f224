// A minimal fork-join parallel loop on std::thread.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <vector>

namespace symembed {

// Number of worker threads to use when the caller passes 0: the hardware concurrency
// (at least 1), overridable with the environment variable SYMEMBED_THREADS.
int DefaultThreadCount();

// Calls fn(i) for i in [0, n) on up to `threads` threads (0 = DefaultThreadCount()), handing out
// indices dynamically in chunks of `grain`. The first exception thrown by fn is rethrown in the
// caller after all threads have stopped.
void ParallelFor(int n, const std::function<void(int)>& fn, int threads = 0, int grain = 1);

// Fills a #sources x n matrix in parallel over sources: row_fn(i, out) writes the n distances
// of source i to out (a contiguous per-thread buffer). Throws InvalidInputError for a source
// outside [0, n).
Eigen::MatrixXd ParallelRows(const std::vector<int>& sources, int n, int threads,
                             const std::function<void(int, double*)>& row_fn);

}  // namespace symembed

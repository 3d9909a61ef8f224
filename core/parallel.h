// A minimal fork-join parallel loop on std::thread.
#pragma once

#include <functional>

namespace symembed {

// Number of worker threads to use when the caller passes 0: the hardware concurrency
// (at least 1), overridable with the environment variable SYMEMBED_THREADS.
int DefaultThreadCount();

// Calls fn(i) for i in [0, n) on up to `threads` threads (0 = DefaultThreadCount()), handing out
// indices dynamically in chunks of `grain`. The first exception thrown by fn is rethrown in the
// caller after all threads have stopped.
void ParallelFor(int n, const std::function<void(int)>& fn, int threads = 0, int grain = 1);

}  // namespace symembed

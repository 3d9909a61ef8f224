// Wall-clock seconds for the stage timings the harness records.
#pragma once

#include <chrono>

namespace symembed {

// Seconds elapsed on the steady clock since `start`.
inline double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace symembed

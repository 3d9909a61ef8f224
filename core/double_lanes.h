// Vectors of doubles in GCC's vector extension, for kernels compiled once per instruction set:
// 8 lanes (one zmm register) for an AVX-512 build, 4 (one ymm register) for AVX2, 2 (one xmm
// register) for the x86-64 baseline. Each lane does the same scalar arithmetic.
#pragma once

#include <cstdint>

namespace symembed {

template <int kLanes>
struct DoubleLanes {
  typedef double Doubles __attribute__((vector_size(8 * kLanes)));
  typedef int64_t Bits __attribute__((vector_size(8 * kLanes)));
  // For loads at addresses aligned to a double only.
  typedef double DoublesUnaligned __attribute__((vector_size(8 * kLanes), aligned(8)));
};

}  // namespace symembed

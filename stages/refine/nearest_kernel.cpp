#include "stages/refine/nearest_kernel.h"

#include <algorithm>
#include <limits>

#include "core/errors.h"

namespace symembed {
namespace {

// Vectors of floats and ints in GCC's vector extension: 8 lanes (one ymm register) for the AVX2
// build, 4 (one xmm register) for the baseline. Each lane does the same scalar arithmetic.
template <int kLanes>
struct Vectors {
  typedef float Floats __attribute__((vector_size(4 * kLanes)));
  typedef int Ints __attribute__((vector_size(4 * kLanes)));
  // For loads at addresses aligned to a float only.
  typedef float FloatsUnaligned __attribute__((vector_size(4 * kLanes), aligned(4)));
};

// The kernel over whole blocks of points, for kTile queries per pass over the points. Its
// kTile x (kNearestBlock / kLanes) accumulators stay in registers: 4 x 3 of the 16 ymm registers
// in the AVX2 build, 2 x 6 of the 16 xmm registers in the baseline one. The tiling changes the
// order of nothing: every dot product is its own sum in dimension order.
template <int kLanes, int kTile>
__attribute__((always_inline)) inline void NearestBlocks(const float* coords,
                                                         const float* sq_norms, int blocks,
                                                         int dims, const float* queries, int m,
                                                         int* nearest) {
  using Floats = typename Vectors<kLanes>::Floats;
  using Ints = typename Vectors<kLanes>::Ints;
  using FloatsUnaligned = typename Vectors<kLanes>::FloatsUnaligned;
  constexpr int kVectors = kNearestBlock / kLanes;  // vectors per block of points
  static_assert(kNearestBlock % kLanes == 0, "a block is whole vectors");
  Ints lane;
  for (int l = 0; l < kLanes; ++l) lane[l] = l;
  const float inf = std::numeric_limits<float>::infinity();
  for (int q0 = 0; q0 < m; q0 += kTile) {
    // A short last tile repeats its last query; only the real queries' results are written.
    const float* q[kTile];
    for (int t = 0; t < kTile; ++t) {
      q[t] = queries + static_cast<long>(std::min(q0 + t, m - 1)) * dims;
    }
    Floats best[kTile];
    Ints arg[kTile];
    for (int t = 0; t < kTile; ++t) {
      best[t] = Floats{} + inf;
      arg[t] = Ints{};
    }
    for (int b = 0; b < blocks; ++b) {
      const float* block = coords + static_cast<long>(b) * dims * kNearestBlock;
      Floats acc[kTile][kVectors] = {};
      for (int c = 0; c < dims; ++c) {
        Floats p[kVectors];
        for (int v = 0; v < kVectors; ++v) {
          p[v] = *reinterpret_cast<const FloatsUnaligned*>(block + c * kNearestBlock + v * kLanes);
        }
        for (int t = 0; t < kTile; ++t) {
          const float x = q[t][c];
          for (int v = 0; v < kVectors; ++v) acc[t][v] = acc[t][v] + x * p[v];
        }
      }
      for (int v = 0; v < kVectors; ++v) {
        const Floats norms =
            *reinterpret_cast<const FloatsUnaligned*>(sq_norms + b * kNearestBlock + v * kLanes);
        const Ints index = lane + (b * kNearestBlock + v * kLanes);
        for (int t = 0; t < kTile; ++t) {
          const Floats d = norms - 2.0f * acc[t][v];
          // Strictly lower: within a lane the indices grow, so the first minimum is kept.
          const Ints lower = d < best[t];
          best[t] = lower ? d : best[t];
          arg[t] = lower ? index : arg[t];
        }
      }
    }
    for (int t = 0; t < kTile && q0 + t < m; ++t) {
      float value = best[t][0];
      int index = arg[t][0];
      for (int l = 1; l < kLanes; ++l) {
        if (best[t][l] < value || (best[t][l] == value && arg[t][l] < index)) {
          value = best[t][l];
          index = arg[t][l];
        }
      }
      nearest[q0 + t] = index;
    }
  }
}

__attribute__((target("avx2"))) void NearestBlocksAvx2(const float* coords,
                                                     const float* sq_norms, int blocks, int dims,
                                                     const float* queries, int m, int* nearest) {
  NearestBlocks<8, 4>(coords, sq_norms, blocks, dims, queries, m, nearest);
}

void NearestBlocksBaseline(const float* coords, const float* sq_norms, int blocks, int dims,
                           const float* queries, int m, int* nearest) {
  NearestBlocks<4, 2>(coords, sq_norms, blocks, dims, queries, m, nearest);
}

}  // namespace

bool NearestKernelHasAvx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
}

PackedPoints PackPoints(const float* points, int n, int dims, int stride) {
  SYMEMBED_CHECK(n > 0 && dims > 0 && stride >= n,
                 "packing " << n << " points of " << dims << " dimensions, stride " << stride);
  const int blocks = (n + kNearestBlock - 1) / kNearestBlock;
  PackedPoints packed;
  packed.count = n;
  packed.dims = dims;
  packed.coords.assign(static_cast<size_t>(blocks) * dims * kNearestBlock, 0.0f);
  packed.sq_norms.assign(static_cast<size_t>(blocks) * kNearestBlock,
                         std::numeric_limits<float>::infinity());
  for (int i = 0; i < n; ++i) {
    const int b = i / kNearestBlock, slot = i % kNearestBlock;
    float* block = packed.coords.data() + static_cast<size_t>(b) * dims * kNearestBlock;
    float norm = 0.0f;
    for (int c = 0; c < dims; ++c) {
      const float x = points[i + static_cast<size_t>(c) * stride];
      block[c * kNearestBlock + slot] = x;
      norm = norm + x * x;
    }
    packed.sq_norms[i] = norm;
  }
  return packed;
}

void NearestPacked(const PackedPoints& points, const float* queries, int m, int* nearest,
                   NearestIsa isa) {
  if (m <= 0) return;
  SYMEMBED_CHECK(isa != NearestIsa::kAvx2 || NearestKernelHasAvx2(),
                 "nearest kernel: AVX2 asked for on a processor without it");
  const int blocks = static_cast<int>(points.sq_norms.size()) / kNearestBlock;
  const bool avx2 = isa == NearestIsa::kAvx2 || (isa == NearestIsa::kAuto && NearestKernelHasAvx2());
  (avx2 ? NearestBlocksAvx2 : NearestBlocksBaseline)(points.coords.data(), points.sq_norms.data(),
                                                     blocks, points.dims, queries, m, nearest);
}

}  // namespace symembed

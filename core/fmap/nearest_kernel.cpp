#include "core/fmap/nearest_kernel.h"

#include <algorithm>
#include <limits>

#include "core/errors.h"

namespace symembed {
namespace {

// Vectors of floats and ints in GCC's vector extension: 16 lanes (one zmm register) for the
// AVX-512 build, 8 (one ymm register) for the AVX2 build, 4 (one xmm register) for the baseline.
// Each lane does the same scalar arithmetic.
template <int kLanes>
struct Vectors {
  typedef float Floats __attribute__((vector_size(4 * kLanes)));
  typedef int Ints __attribute__((vector_size(4 * kLanes)));
  // For loads at addresses aligned to a float only.
  typedef float FloatsUnaligned __attribute__((vector_size(4 * kLanes), aligned(4)));
};

// The kernel over whole blocks of points, for kTile queries per pass over the points. A block is
// taken kVectors vectors (kVectors x kLanes points) at a time, so its kTile x kVectors
// accumulators stay in registers: 8 x 3 of the 32 zmm registers in the AVX-512 build, 4 x 3 of
// the 16 ymm registers in the AVX2 one, 2 x 6 of the 16 xmm registers in the baseline one. The
// tiling changes the order of nothing: every dot product is its own sum in dimension order.
template <int kLanes, int kTile, int kVectors>
__attribute__((always_inline)) inline void NearestBlocks(const float* coords,
                                                         const float* sq_norms, int blocks,
                                                         int dims, const float* queries, int m,
                                                         int* nearest) {
  using Floats = typename Vectors<kLanes>::Floats;
  using Ints = typename Vectors<kLanes>::Ints;
  using FloatsUnaligned = typename Vectors<kLanes>::FloatsUnaligned;
  constexpr int kWidth = kVectors * kLanes;  // points per part of a block
  static_assert(kNearestBlock % kWidth == 0, "a block is whole parts");
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
      for (int part = 0; part < kNearestBlock; part += kWidth) {
        const float* block = coords + static_cast<long>(b) * dims * kNearestBlock + part;
        Floats acc[kTile][kVectors] = {};
        for (int c = 0; c < dims; ++c) {
          Floats p[kVectors];
          for (int v = 0; v < kVectors; ++v) {
            p[v] =
                *reinterpret_cast<const FloatsUnaligned*>(block + c * kNearestBlock + v * kLanes);
          }
          for (int t = 0; t < kTile; ++t) {
            const float x = q[t][c];
            for (int v = 0; v < kVectors; ++v) acc[t][v] = acc[t][v] + x * p[v];
          }
        }
        const int first = b * kNearestBlock + part;  // index of the part's first point
        for (int v = 0; v < kVectors; ++v) {
          const Floats norms =
              *reinterpret_cast<const FloatsUnaligned*>(sq_norms + first + v * kLanes);
          const Ints index = lane + (first + v * kLanes);
          for (int t = 0; t < kTile; ++t) {
            const Floats d = norms - 2.0f * acc[t][v];
            // Strictly lower: within a lane the indices grow, so the first minimum is kept.
            const Ints lower = d < best[t];
            best[t] = lower ? d : best[t];
            arg[t] = lower ? index : arg[t];
          }
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

__attribute__((target("avx512f"))) void NearestBlocksAvx512(const float* coords,
                                                          const float* sq_norms, int blocks,
                                                          int dims, const float* queries, int m,
                                                          int* nearest) {
  NearestBlocks<16, 8, 3>(coords, sq_norms, blocks, dims, queries, m, nearest);
}

__attribute__((target("avx2"))) void NearestBlocksAvx2(const float* coords,
                                                     const float* sq_norms, int blocks, int dims,
                                                     const float* queries, int m, int* nearest) {
  NearestBlocks<8, 4, 3>(coords, sq_norms, blocks, dims, queries, m, nearest);
}

void NearestBlocksBaseline(const float* coords, const float* sq_norms, int blocks, int dims,
                           const float* queries, int m, int* nearest) {
  NearestBlocks<4, 2, 6>(coords, sq_norms, blocks, dims, queries, m, nearest);
}

}  // namespace

NearestIsa ResolveNearestIsa(NearestIsa isa) {
  if (isa != NearestIsa::kAuto) return isa;
  if (NearestKernelSupports(NearestIsa::kAvx512)) return NearestIsa::kAvx512;
  if (NearestKernelSupports(NearestIsa::kAvx2)) return NearestIsa::kAvx2;
  return NearestIsa::kBaseline;
}

bool NearestKernelSupports(NearestIsa isa) {
  // __builtin_cpu_supports also checks that the operating system saves the wider registers.
  static const bool avx512 = __builtin_cpu_supports("avx512f");
  static const bool avx2 = __builtin_cpu_supports("avx2");
  switch (isa) {
    case NearestIsa::kAvx512:
      return avx512;
    case NearestIsa::kAvx2:
      return avx2;
    default:
      return true;
  }
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
  // Block by block, dimension by dimension: the input is read a column at a time, and each
  // point's ||p||^2 is still summed in dimension order.
  for (int b = 0; b < blocks; ++b) {
    const int first = b * kNearestBlock, count = std::min(kNearestBlock, n - first);
    float* block = packed.coords.data() + static_cast<size_t>(b) * dims * kNearestBlock;
    float* norms = packed.sq_norms.data() + first;
    std::fill(norms, norms + count, 0.0f);
    for (int c = 0; c < dims; ++c) {
      const float* column = points + static_cast<size_t>(c) * stride + first;
      float* out = block + c * kNearestBlock;
      for (int slot = 0; slot < count; ++slot) {
        const float x = column[slot];
        out[slot] = x;
        norms[slot] = norms[slot] + x * x;
      }
    }
  }
  return packed;
}

void NearestPacked(const PackedPoints& points, const float* queries, int m, int* nearest,
                   NearestIsa isa) {
  if (m <= 0) return;
  SYMEMBED_CHECK(NearestKernelSupports(isa),
                 "nearest kernel: a build this processor cannot run was asked for");
  const int blocks = static_cast<int>(points.sq_norms.size()) / kNearestBlock;
  const float* coords = points.coords.data();
  const float* norms = points.sq_norms.data();
  switch (ResolveNearestIsa(isa)) {
    case NearestIsa::kAvx512:
      NearestBlocksAvx512(coords, norms, blocks, points.dims, queries, m, nearest);
      break;
    case NearestIsa::kAvx2:
      NearestBlocksAvx2(coords, norms, blocks, points.dims, queries, m, nearest);
      break;
    default:
      NearestBlocksBaseline(coords, norms, blocks, points.dims, queries, m, nearest);
  }
}

}  // namespace symembed

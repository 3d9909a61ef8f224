// Exact nearest neighbours by brute force in single precision, for the spectral embeddings of
// functional-map refinement (tens to a few hundred dimensions, where a kd-tree prunes nothing).
//
// For a query q the nearest point minimises ||p||^2 - 2 q.p (||q||^2 is common to all points).
// The kernel computes that for a tile of queries (8 with AVX-512) against a part of a block of 48
// points at a time, the dot products held in registers as they accumulate dimension by
// dimension, and keeps per query the running minimum and the first point attaining it. Nothing
// of size queries x points is stored: one pass over the points per tile, with the block's
// coordinates contiguous.
//
// The arithmetic is fixed: each dot product is summed in dimension order, a multiply then an add
// (never fused), so the result is the same bit for bit on every x86-64 machine. The kernel is
// compiled three times, for AVX-512 (16 lanes per instruction), AVX2 (8 lanes) and the x86-64
// baseline (SSE2, 4 lanes), and the widest the processor supports is chosen at run time.
#pragma once

#include <vector>

namespace symembed {

// Points in the kernel's layout: blocks of kNearestBlock points, each block stored dimension by
// dimension (the block's kNearestBlock coordinates of dimension 0, then of dimension 1, ...). The
// last block is padded with points at infinite distance.
struct PackedPoints {
  int count = 0;              // points, without the padding
  int dims = 0;
  std::vector<float> coords;  // blocks x dims x kNearestBlock
  std::vector<float> sq_norms;  // ||p||^2 per point, summed in dimension order; +inf for padding
};

constexpr int kNearestBlock = 48;

// Packs n points of `dims` coordinates; point i's coordinate c is at points[i + c * stride] (an
// n x dims column-major matrix with leading dimension `stride`).
PackedPoints PackPoints(const float* points, int n, int dims, int stride);

enum class NearestIsa { kAuto, kAvx512, kAvx2, kBaseline };

// Whether this processor runs that build of the kernel (kAuto and kBaseline: always).
bool NearestKernelSupports(NearestIsa isa);

// The build for `isa`: itself, or for kAuto the widest this processor runs.
NearestIsa ResolveNearestIsa(NearestIsa isa);

// For each of m queries (row-major: query r's coordinates at queries[r * dims ...]), writes to
// nearest[r] the index of the point minimising ||p||^2 - 2 q.p, the lowest index among equal
// values. A query whose every value is NaN gets 0. `isa` forces one build of the kernel (one the
// processor does not support throws); all give the same result.
void NearestPacked(const PackedPoints& points, const float* queries, int m, int* nearest,
                   NearestIsa isa = NearestIsa::kAuto);

}  // namespace symembed

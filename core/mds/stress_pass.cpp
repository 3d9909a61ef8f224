#include "core/mds/stress_pass.h"

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/errors.h"
#include "core/parallel.h"

namespace symembed {

namespace {

// The pairs are split over a fixed number of lanes, each with its own accumulators, so the
// summation order (and the result) does not depend on the thread count.
constexpr int kLanes = 16;
constexpr int kRowBlock = 8;
constexpr int kMaxKernelDims = 4;

// Row i of the pass: the pairs (i, j), j = i + 1 .. i + len. Pointers start at row i + 1.
struct Row {
  int len = 0;
  const double* x[kMaxKernelDims] = {};  // X's columns
  double xi[kMaxKernelDims] = {};        // x_i
  const double* d = nullptr;             // column i of D
  const double* w = nullptr;             // column i of W, or null
  double* acc[kMaxKernelDims] = {};      // the lane's B(X) X columns, or null
};

// What row i adds: to the lane's stress, and what it subtracts from (B(X) X)_i.
struct RowSums {
  double stress = 0.0;
  double bx[kMaxKernelDims] = {};
};

// Pair j of a row: its stress term and w d / ||x_i - x_j|| (x_j - x_i), each operation as the
// baseline's expressions do it; adds the latter to the row j of the lane's B(X) X.
template <int Dims, bool Weighted, bool WithBx>
inline void PairTerms(const Row& r, int j, double* stress, double* bx) {
  double dx[Dims];
  for (int c = 0; c < Dims; ++c) dx[c] = r.x[c][j] - r.xi[c];
  double d2 = dx[0] * dx[0];
  for (int c = 1; c < Dims; ++c) d2 = d2 + dx[c] * dx[c];
  const double dist = std::sqrt(d2);
  const double t = r.d[j] - dist;
  *stress = Weighted ? r.w[j] * (t * t) : t * t;
  if (!WithBx) return;
  const double num = Weighted ? r.w[j] * r.d[j] : r.d[j];
  const double ratio = dist > 0.0 ? num / dist : 0.0;
  for (int c = 0; c < Dims; ++c) {
    bx[c] = ratio * dx[c];
    r.acc[c][j] = r.acc[c][j] + bx[c];
  }
}

// Pairs j .. j + 3 of a row, as PairTerms.
template <int Dims, bool Weighted, bool WithBx>
__attribute__((target("avx2"))) inline void PairTermsAvx2(const Row& r, const __m256d* xi, int j,
                                                          __m256d* stress, __m256d* bx) {
  __m256d dx[Dims];
  for (int c = 0; c < Dims; ++c) dx[c] = _mm256_sub_pd(_mm256_loadu_pd(r.x[c] + j), xi[c]);
  __m256d d2 = _mm256_mul_pd(dx[0], dx[0]);
  for (int c = 1; c < Dims; ++c) d2 = _mm256_add_pd(d2, _mm256_mul_pd(dx[c], dx[c]));
  const __m256d dist = _mm256_sqrt_pd(d2);
  const __m256d d = _mm256_loadu_pd(r.d + j);
  const __m256d t = _mm256_sub_pd(d, dist);
  __m256d num = d;
  *stress = _mm256_mul_pd(t, t);
  if (Weighted) {
    const __m256d w = _mm256_loadu_pd(r.w + j);
    *stress = _mm256_mul_pd(w, *stress);
    num = _mm256_mul_pd(w, d);
  }
  if (!WithBx) return;
  const __m256d positive = _mm256_cmp_pd(dist, _mm256_setzero_pd(), _CMP_GT_OQ);
  const __m256d ratio = _mm256_and_pd(positive, _mm256_div_pd(num, dist));
  for (int c = 0; c < Dims; ++c) {
    bx[c] = _mm256_mul_pd(ratio, dx[c]);
    double* a = r.acc[c] + j;
    _mm256_storeu_pd(a, _mm256_add_pd(_mm256_loadu_pd(a), bx[c]));
  }
}

// Sums a row's terms in the order of Eigen 3.4's reduction of a dynamic expression on SSE2
// (two-lane packets, two accumulators): below 4 terms from the first on, one after another;
// else the 4-lane accumulator of terms 4k + l (l = 0..3), started from terms 0..3, folded to
// (a0 + a2, a1 + a3), plus terms n4 and n4 + 1 when 2 or 3 are left, the two lanes summed, then
// the last term when the count is odd.
template <int Dims, bool Weighted, bool WithBx>
__attribute__((target("avx2"))) RowSums RowAvx2(const Row& r) {
  constexpr int kSums = WithBx ? 1 + Dims : 1;
  const int len = r.len;
  double term[kSums];
  RowSums out;
  double* sums[1 + kMaxKernelDims] = {&out.stress, &out.bx[0], &out.bx[1], &out.bx[2], &out.bx[3]};
  if (len < 4) {
    for (int j = 0; j < len; ++j) {
      PairTerms<Dims, Weighted, WithBx>(r, j, &term[0], &term[1]);
      for (int k = 0; k < kSums; ++k) *sums[k] = j == 0 ? term[k] : *sums[k] + term[k];
    }
    return out;
  }
  __m256d xi[Dims];
  for (int c = 0; c < Dims; ++c) xi[c] = _mm256_set1_pd(r.xi[c]);
  __m256d acc[kSums], next[kSums];
  PairTermsAvx2<Dims, Weighted, WithBx>(r, xi, 0, &acc[0], &acc[1]);
  const int n4 = len & ~3;
  for (int j = 4; j < n4; j += 4) {
    PairTermsAvx2<Dims, Weighted, WithBx>(r, xi, j, &next[0], &next[1]);
    for (int k = 0; k < kSums; ++k) acc[k] = _mm256_add_pd(acc[k], next[k]);
  }
  double lo[kSums], hi[kSums];
  for (int k = 0; k < kSums; ++k) {
    const __m128d half =
        _mm_add_pd(_mm256_castpd256_pd128(acc[k]), _mm256_extractf128_pd(acc[k], 1));
    lo[k] = _mm_cvtsd_f64(half);
    hi[k] = _mm_cvtsd_f64(_mm_unpackhi_pd(half, half));
  }
  if (len - n4 >= 2) {
    PairTerms<Dims, Weighted, WithBx>(r, n4, &term[0], &term[1]);
    for (int k = 0; k < kSums; ++k) lo[k] = lo[k] + term[k];
    PairTerms<Dims, Weighted, WithBx>(r, n4 + 1, &term[0], &term[1]);
    for (int k = 0; k < kSums; ++k) hi[k] = hi[k] + term[k];
  }
  for (int k = 0; k < kSums; ++k) *sums[k] = lo[k] + hi[k];
  if (len % 2 == 1) {
    PairTerms<Dims, Weighted, WithBx>(r, len - 1, &term[0], &term[1]);
    for (int k = 0; k < kSums; ++k) *sums[k] = *sums[k] + term[k];
  }
  return out;
}

template <int Dims>
RowSums RowAvx2ForDims(const Row& r, bool weighted, bool with_bx) {
  if (weighted) return with_bx ? RowAvx2<Dims, true, true>(r) : RowAvx2<Dims, true, false>(r);
  return with_bx ? RowAvx2<Dims, false, true>(r) : RowAvx2<Dims, false, false>(r);
}

RowSums RowKernelAvx2(const Row& r, int dims, bool weighted, bool with_bx) {
  switch (dims) {
    case 1:
      return RowAvx2ForDims<1>(r, weighted, with_bx);
    case 2:
      return RowAvx2ForDims<2>(r, weighted, with_bx);
    case 3:
      return RowAvx2ForDims<3>(r, weighted, with_bx);
    default:
      return RowAvx2ForDims<4>(r, weighted, with_bx);
  }
}

}  // namespace

double StressPass(const Eigen::MatrixXd& D, const Eigen::MatrixXd* W, const Eigen::MatrixXd& X,
                  Eigen::MatrixXd* BX, int threads, NearestIsa isa) {
  SYMEMBED_CHECK(NearestKernelSupports(isa),
                 "stress pass: a build this processor cannot run was asked for");
  const int n = static_cast<int>(D.rows());
  const int dims = static_cast<int>(X.cols());
  const bool avx2 = isa != NearestIsa::kBaseline && NearestKernelSupports(NearestIsa::kAvx2) &&
                    dims >= 1 && dims <= kMaxKernelDims;
  const int blocks = (n + kRowBlock - 1) / kRowBlock;
  std::vector<double> lane_stress(kLanes, 0.0);
  std::vector<Eigen::MatrixXd> lane_bx(BX != nullptr ? kLanes : 0);
  ParallelFor(
      kLanes,
      [&](int lane) {
        Eigen::ArrayXd dist(avx2 ? 0 : n), ratio(avx2 ? 0 : n);
        Eigen::ArrayXXd diff(avx2 ? 0 : n, dims);
        Eigen::MatrixXd* acc = nullptr;
        if (BX != nullptr) {
          lane_bx[lane].setZero(n, dims);
          acc = &lane_bx[lane];
        }
        double sum = 0.0;
        // Blocks are dealt round-robin so every lane gets long and short rows alike.
        for (int b = lane; b < blocks; b += kLanes) {
          const int end = std::min(n, (b + 1) * kRowBlock);
          for (int i = b * kRowBlock; i < end; ++i) {
            const int len = n - i - 1;
            if (len == 0) continue;
            if (avx2) {
              Row r;
              r.len = len;
              for (int c = 0; c < dims; ++c) {
                r.x[c] = X.col(c).data() + i + 1;
                r.xi[c] = X(i, c);
                if (acc != nullptr) r.acc[c] = acc->col(c).data() + i + 1;
              }
              r.d = D.col(i).data() + i + 1;
              if (W != nullptr) r.w = W->col(i).data() + i + 1;
              const RowSums s = RowKernelAvx2(r, dims, W != nullptr, acc != nullptr);
              sum += s.stress;
              if (acc != nullptr) {
                for (int c = 0; c < dims; ++c) (*acc)(i, c) -= s.bx[c];
              }
              continue;
            }
            auto dx = diff.topRows(len);
            auto di = dist.head(len);
            for (int c = 0; c < dims; ++c) {
              dx.col(c) = X.col(c).segment(i + 1, len).array() - X(i, c);
            }
            di = dx.square().rowwise().sum().sqrt();
            const auto Dt = D.col(i).segment(i + 1, len).array();
            auto ri = ratio.head(len);
            if (W != nullptr) {
              const auto Wt = W->col(i).segment(i + 1, len).array();
              sum += (Wt * (Dt - di).square()).sum();
              if (acc != nullptr) ri = (di > 0.0).select(Wt * Dt / di, 0.0);
            } else {
              sum += (Dt - di).square().sum();
              if (acc != nullptr) ri = (di > 0.0).select(Dt / di, 0.0);
            }
            if (acc != nullptr) {
              for (int c = 0; c < dims; ++c) {
                // x_i - x_j = -dx for row i; x_j - x_i = dx for the rows j.
                (*acc)(i, c) -= (ri * dx.col(c)).sum();
                acc->col(c).segment(i + 1, len).array() += ri * dx.col(c);
              }
            }
          }
        }
        lane_stress[lane] = sum;
      },
      threads);
  double total = 0.0;
  for (double s : lane_stress) total += s;
  if (BX != nullptr) {
    BX->setZero(n, dims);
    for (const Eigen::MatrixXd& a : lane_bx) *BX += a;
  }
  return total;
}

}  // namespace symembed

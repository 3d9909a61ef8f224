#include "core/parallel.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

#include "core/errors.h"

namespace symembed {

int DefaultThreadCount() {
  if (const char* env = std::getenv("SYMEMBED_THREADS")) {
    const int n = std::atoi(env);
    if (n > 0) return n;
  }
  return std::max(1u, std::thread::hardware_concurrency());
}

void ParallelFor(int n, const std::function<void(int)>& fn, int threads, int grain) {
  if (n <= 0) return;
  if (threads <= 0) threads = DefaultThreadCount();
  grain = std::max(1, grain);
  threads = std::min(threads, (n + grain - 1) / grain);
  if (threads <= 1) {
    for (int i = 0; i < n; ++i) fn(i);
    return;
  }
  std::atomic<int> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&]() {
    while (!failed.load()) {
      const int begin = next.fetch_add(grain);
      if (begin >= n) break;
      const int end = std::min(n, begin + grain);
      try {
        for (int i = begin; i < end; ++i) fn(i);
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

Eigen::MatrixXd ParallelRows(const std::vector<int>& sources, int n, int threads,
                             const std::function<void(int, double*)>& row_fn) {
  for (int s : sources) {
    if (s < 0 || s >= n) {
      throw InvalidInputError("geodesic source " + std::to_string(s) +
                              " is not a vertex id in [0, " + std::to_string(n) + ")");
    }
  }
  const int m = static_cast<int>(sources.size());
  Eigen::MatrixXd D(m, n);
  // Rows are computed into a contiguous row-major buffer of kBlock sources and copied as a
  // block: D is column-major, so each column then receives kBlock adjacent values instead of
  // one strided write per source.
  constexpr int kBlock = 16;
  const int blocks = (m + kBlock - 1) / kBlock;
  ParallelFor(
      blocks,
      [&](int b) {
        using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
        thread_local RowMajor buffer;
        const int begin = b * kBlock, count = std::min(kBlock, m - begin);
        buffer.resize(count, n);
        for (int i = 0; i < count; ++i) row_fn(begin + i, buffer.row(i).data());
        D.middleRows(begin, count) = buffer;
      },
      threads);
  return D;
}

}  // namespace symembed

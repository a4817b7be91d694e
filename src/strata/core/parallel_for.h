#pragma once
// Work sharing over std::thread for every CPU stage (meshing, ESDF queries, the reference
// kernels, the simulator's sensors): the one way the project splits a loop over threads.
// Thread safety: `work` runs concurrently on disjoint index ranges; it must write only to its own
// items. The first exception thrown by any range is rethrown in the caller after all threads join.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace strata {

inline int resolveThreadCount(int requested) {
  if (requested > 0) return requested;
  return std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
}

/// Calls work(begin, end) on chunks of [0, count) from `threads` threads (the caller is one of
/// them). Chunks are claimed dynamically; work must write only to its own items. The first
/// exception thrown by any chunk is rethrown here after all threads have joined.
template <typename Work>
void parallelForChunks(std::size_t count, int threads, std::size_t chunk, Work&& work) {
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto run = [&] {
    try {
      for (std::size_t begin = next.fetch_add(chunk); begin < count;
           begin = next.fetch_add(chunk)) {
        work(begin, std::min(count, begin + chunk));
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next = count;  // stop the others early
    }
  };
  const std::size_t chunks = (count + chunk - 1) / chunk;
  const int helpers = static_cast<int>(std::min<std::size_t>(chunks, threads)) - 1;
  std::vector<std::thread> pool;
  for (int i = 0; i < helpers; ++i) pool.emplace_back(run);
  run();
  for (std::thread& t : pool) t.join();
  if (error) std::rethrow_exception(error);
}

/// Calls fn(begin, end) on contiguous blocks of [0, count), one block per thread: `threads` threads
/// (0 = hardware concurrency), inline when one suffices.
inline void parallelForBlocks(int count, int threads,
                              const std::function<void(int begin, int end)>& fn) {
  if (count <= 0) return;
  const int n = std::min(resolveThreadCount(threads), count);
  if (n == 1) {
    fn(0, count);
    return;
  }
  const std::size_t block = (static_cast<std::size_t>(count) + n - 1) / n;
  parallelForChunks(static_cast<std::size_t>(count), n, block,
                    [&](std::size_t begin, std::size_t end) {
                      fn(static_cast<int>(begin), static_cast<int>(end));
                    });
}

/// Calls fn(i) for every i in [0, count) on `threads` threads (0 = hardware concurrency), items
/// claimed one at a time (for items of very different cost).
template <typename Fn>
void parallelForEach(std::size_t count, int threads, Fn&& fn) {
  parallelForChunks(count, resolveThreadCount(threads), 1,
                    [&](std::size_t begin, std::size_t end) {
                      for (std::size_t i = begin; i < end; ++i) fn(i);
                    });
}

}  // namespace strata

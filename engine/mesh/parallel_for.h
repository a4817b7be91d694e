#pragma once
// Minimal work sharing over std::thread for the mesher (internal).
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace strata::detail {

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

}  // namespace strata::detail

#pragma once
// Splits [0, count) into contiguous blocks, one per thread. The split never changes results: every
// caller writes disjoint outputs and draws random numbers from per-row streams.
#include <functional>

namespace strata::sim {

/// Calls fn(begin, end) on up to `threads` threads (0 = hardware concurrency), blocks until all
/// return, and rethrows the first exception. Runs inline when one thread suffices.
void parallelFor(int count, int threads, const std::function<void(int begin, int end)>& fn);

}  // namespace strata::sim

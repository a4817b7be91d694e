#pragma once
// Wall time for the statistics every stage reports (milliseconds on the steady clock).
// Thread safety: all functions are thread safe.
#include <chrono>

namespace strata {

using SteadyClock = std::chrono::steady_clock;

/// Milliseconds of wall time from `start` to now (steady clock; never negative).
inline double msSince(SteadyClock::time_point start) {
  return std::chrono::duration<double, std::milli>(SteadyClock::now() - start).count();
}

/// Seconds of wall time from `start` to now (steady clock).
inline double secondsSince(SteadyClock::time_point start) {
  return std::chrono::duration<double>(SteadyClock::now() - start).count();
}

}  // namespace strata

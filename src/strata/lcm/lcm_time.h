#pragma once
// Time stamps of messages: microseconds since the Unix epoch (LCM's utime convention).
#include <cstdint>

namespace strata::lcm_io {

/// Wall-clock now, microseconds since the Unix epoch.
std::int64_t nowUtime();

/// Seconds (dataset timestamps) to utime, rounded to the nearest microsecond.
std::int64_t secondsToUtime(double t_s);

}  // namespace strata::lcm_io

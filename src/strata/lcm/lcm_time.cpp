#include "strata/lcm/lcm_time.h"

#include <chrono>
#include <cmath>

namespace strata::lcm_io {

std::int64_t nowUtime() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::int64_t secondsToUtime(double t_s) { return std::llround(t_s * 1e6); }

}  // namespace strata::lcm_io

#pragma once
// The device's streaming ceiling: GB/s a trivial copy kernel (shaders/vk/stream_copy.comp, vec4
// accesses, 256-invocation workgroups) moves, read plus written, measured with timestamps.
#include "strata/vk/vk.h"

namespace strata::bench {

struct StreamingCeiling {
  double gb_per_s = 0.0;      // median of the repetitions, bytes read + written per second / 1e9
  double buffer_mib = 0.0;    // size of each of the two buffers
  int repetitions = 0;
};

/// Copies a buffer of `buffer_mib` MiB `repetitions` times (after one warm-up copy).
StreamingCeiling measureStreamingCeiling(vk::Context& context, double buffer_mib = 64.0,
                                         int repetitions = 7);

}  // namespace strata::bench

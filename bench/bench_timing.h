#pragma once
// Small helpers shared by strata-bench's subcommands: wall time and the default data folder.
#include <chrono>
#include <filesystem>
#include <string>

namespace strata::bench {

using Clock = std::chrono::steady_clock;

/// Milliseconds of wall time from `start` to now.
inline double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

/// The redkitchen frames in the shared test data, the default input of the fusion, ESDF and
/// tracking benchmarks.
inline std::string redkitchenDataDir() {
  return std::filesystem::path(STRATA_SHARED_DATA_DIR "/redkitchen").lexically_normal().string();
}

}  // namespace strata::bench

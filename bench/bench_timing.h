#pragma once
// Small helpers shared by strata-bench's subcommands: wall time and the default data folder.
#include <chrono>
#include <filesystem>
#include <string>

#include "strata/core/clock.h"

namespace strata::bench {

using Clock = std::chrono::steady_clock;

/// The redkitchen frames in the shared test data, the default input of the fusion, ESDF and
/// tracking benchmarks.
inline std::string redkitchenDataDir() {
  return std::filesystem::path(STRATA_SHARED_DATA_DIR "/redkitchen").lexically_normal().string();
}

}  // namespace strata::bench

#pragma once
// SIGINT/SIGTERM as a flag the LCM processes poll between messages, so that they stop cleanly:
// strata-mapper saves its map, strata-vio writes its summary.
#include <atomic>

namespace strata::lcm_io {

/// Installs handlers for SIGINT and SIGTERM (once per process) that set the returned flag.
/// Thread safe; the flag may be read from any thread.
const std::atomic<bool>& installStopSignals();

}  // namespace strata::lcm_io

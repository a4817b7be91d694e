#pragma once
// Where a benchmark ran: CPU, cores, Vulkan device, lavapipe threads, date, commit, load.
#include <cstdint>
#include <string>

#include "json.h"

namespace strata::bench {

/// {"cpu_model", "logical_cores", "device", "lp_num_threads", "date_utc", "git_commit",
///  "build_type", "load_average_at_start", "load_average_at_end"}. `device_name` from
/// vk::Context::deviceName(); `load_at_start` from loadAverage() before the runs.
Json machineInfo(const std::string& device_name, const std::string& load_at_start);

/// The 1, 5 and 15 minute load averages from /proc/loadavg ("unknown" where unreadable).
std::string loadAverage();

/// Peak resident set size of this process so far (getrusage, never below the current RSS), MiB.
double peakRssMiB();
/// Current resident set size (/proc/self/statm), MiB; 0 where unreadable.
double currentRssMiB();

}  // namespace strata::bench

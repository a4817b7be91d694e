#pragma once
// The soak's loop: strata-mapper as a child process, strata-play replaying pre-rendered sessions
// into it one after another (each play ends its session), the mapper sampled once a second.
// Both children run in this process's private network namespace (private_network.h).
// Thread safety: not thread safe; one soak per process.
#include <sys/types.h>

#include <cstdint>
#include <string>
#include <vector>

namespace strata::bench {

struct SoakSettings {
  double duration_s = 120.0;  // no new session starts after this; the open one is finished
  std::string url;            // udpm:// inside the namespace
  std::string mapper_bin, play_bin;
  std::vector<std::string> mapper_args;   // besides --url
  std::vector<std::string> session_dirs;  // TUM folders, played in turn
  int frames_per_session = 0;             // frames in each folder
  std::string log_dir;                    // mapper.log, play.log (the last session's)
  double sample_period_s = 1.0;
};

/// One second of the soak. Memory of the mapper process; counters from its map_stats_t.
struct SoakSample {
  double elapsed_s = 0.0;
  double rss_mib = 0.0, hwm_mib = 0.0;  // VmRSS, VmHWM of /proc/<mapper>/status
  double device_mib = 0.0;              // map_stats_t.device_bytes
  std::int64_t blocks = 0;
  std::int64_t frames_sent = 0;  // by the plays finished so far
  std::int64_t frames_received = 0, frames_fused = 0;
  std::int64_t frames_dropped = 0;  // behind the queue or without a pose
  std::int64_t frames_rejected = 0;
  std::int64_t sessions_completed = 0;  // plays finished (their STOP_SESSION confirmed or not)
};

struct SoakRun {
  std::vector<SoakSample> samples;
  std::vector<double> session_ends_s;  // elapsed time of each play's end
  double first_loop_end_s = 0.0;       // every session played once: the warm-up
  int play_failures = 0;               // plays with a nonzero exit code
  int mapper_exit_code = -1;
};

/// VmRSS and VmHWM of a process, MiB; false where /proc/<pid>/status is unreadable.
bool readProcessMemoryMiB(pid_t pid, double* rss_mib, double* hwm_mib);

/// Runs the loop. Throws Error when the mapper does not come up or dies.
SoakRun runSoak(const SoakSettings& settings);

}  // namespace strata::bench

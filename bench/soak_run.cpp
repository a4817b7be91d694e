#include "soak_run.h"

#include <signal.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <lcm/lcm-cpp.hpp>

#include "child_process.h"
#include "strata/core/error.h"
#include "strata/lcm/channels.h"
#include "player/play_flow.h"
#include "private_network.h"

namespace strata::bench {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kMapperStartTimeoutS = 120.0;  // lavapipe compiles its shaders at start
constexpr double kMapperStopTimeoutS = 120.0;
constexpr int kPumpMs = 50;
constexpr double kBytesPerMiB = 1024.0 * 1024.0;

/// `VmRSS:   1234 kB` -> 1234 (kB), or -1.
double statusKb(const std::string& line, const std::string& key) {
  if (line.compare(0, key.size(), key) != 0) return -1.0;
  return std::stod(line.substr(key.size()));
}

/// For children left running when the soak fails: no clean exit needed.
void stop(pid_t pid) {
  kill(pid, SIGKILL);
  waitProcess(pid);
}

class Soak {
 public:
  explicit Soak(const SoakSettings& s) : s_(s), lcm_(s.url), watcher_(lcm_, lcm_io::kStatsChannel) {
    if (!lcm_.good()) throw InputError("LCM URL '" + s.url + "' could not be opened");
  }
  ~Soak() {
    try {
      if (mapper_ > 0 && !mapperExited()) stop(mapper_);
    } catch (const std::exception&) {  // NOTE: a destructor must not throw; the child is gone
    }
  }

  SoakRun run() {
    startMapper();
    start_ = Clock::now();
    next_sample_s_ = 0.0;
    for (std::size_t n = 0; elapsedS() < s_.duration_s; ++n) {
      playSession(s_.session_dirs[n % s_.session_dirs.size()]);
      if (n + 1 == s_.session_dirs.size()) run_.first_loop_end_s = elapsedS();
    }
    sample();  // the last numbers, after the last session ended
    stopMapper();
    return std::move(run_);
  }

 private:
  double elapsedS() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  void startMapper() {
    std::vector<std::string> args = {"--url", s_.url};
    args.insert(args.end(), s_.mapper_args.begin(), s_.mapper_args.end());
    mapper_ = spawnProcess(s_.mapper_bin, args, s_.log_dir + "/mapper.log", true);
    if (!watcher_.waitFor([&] { return watcher_.heard() || mapperExited(); },
                          kMapperStartTimeoutS) ||
        !watcher_.heard()) {
      throw Error("strata-mapper did not come up (see " + s_.log_dir + "/mapper.log)");
    }
  }

  bool mapperExited() {
    if (run_.mapper_exit_code >= 0) return true;
    int code = 0;
    if (!processExited(mapper_, &code)) return false;
    run_.mapper_exit_code = code;
    return true;
  }

  /// One play of one session; samples while it runs.
  void playSession(const std::string& dir) {
    const std::vector<std::string> args = {dir,    "--rate",           "0",  "--quiet", "--url",
                                           s_.url, "--mapper-timeout", "120"};
    const pid_t play = spawnProcess(s_.play_bin, args, s_.log_dir + "/play.log", true);
    int code = 0;
    while (!processExited(play, &code)) {
      watcher_.pump(kPumpMs);
      if (elapsedS() >= next_sample_s_) sample();
      if (mapperExited()) {
        stop(play);
        throw Error("strata-mapper died (see " + s_.log_dir + "/mapper.log)");
      }
    }
    frames_sent_ += s_.frames_per_session;
    if (code != 0) ++run_.play_failures;
    run_.session_ends_s.push_back(elapsedS());
  }

  void sample() {
    SoakSample x;
    x.elapsed_s = elapsedS();
    readProcessMemoryMiB(mapper_, &x.rss_mib, &x.hwm_mib);
    const map_stats_t& m = watcher_.latest();
    x.device_mib = static_cast<double>(m.device_bytes) / kBytesPerMiB;
    x.blocks = m.blocks;
    x.frames_sent = frames_sent_;
    x.frames_received = m.frames_received;
    x.frames_fused = m.frames_fused;
    x.frames_dropped = m.frames_dropped_backlog + m.frames_dropped_no_pose;
    x.frames_rejected = m.frames_rejected;
    x.sessions_completed = static_cast<std::int64_t>(run_.session_ends_s.size());
    run_.samples.push_back(x);
    next_sample_s_ += s_.sample_period_s;
    if (next_sample_s_ < x.elapsed_s) next_sample_s_ = x.elapsed_s + s_.sample_period_s;
  }

  void stopMapper() {
    if (mapperExited()) return;
    kill(mapper_, SIGTERM);
    const auto deadline = Clock::now() + std::chrono::duration<double>(kMapperStopTimeoutS);
    while (!mapperExited()) {
      if (Clock::now() > deadline) kill(mapper_, SIGKILL);
      watcher_.pump(kPumpMs);
    }
  }

  SoakSettings s_;
  lcm::LCM lcm_;
  apps::MapperWatcher watcher_;
  SoakRun run_;
  pid_t mapper_ = -1;
  Clock::time_point start_;
  double next_sample_s_ = 0.0;
  std::int64_t frames_sent_ = 0;
};

}  // namespace

bool readProcessMemoryMiB(pid_t pid, double* rss_mib, double* hwm_mib) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  if (!in) return false;
  bool rss_seen = false, hwm_seen = false;
  for (std::string line; std::getline(in, line);) {
    if (const double kb = statusKb(line, "VmRSS:"); kb >= 0)
      *rss_mib = kb / 1024.0, rss_seen = true;
    if (const double kb = statusKb(line, "VmHWM:"); kb >= 0)
      *hwm_mib = kb / 1024.0, hwm_seen = true;
  }
  return rss_seen && hwm_seen;
}

SoakRun runSoak(const SoakSettings& settings) {
  if (settings.session_dirs.empty()) throw InputError("no sessions to play");
  enterPrivateNetwork();  // before LCM opens its sockets and the children start
  Soak soak(settings);
  return soak.run();
}

}  // namespace strata::bench

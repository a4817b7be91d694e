#include "kill_trials.h"

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <random>
#include <thread>

#include "strata/core/atomic_file.h"
#include "lcm_process_helpers.h"
#include "strata/map/map_file.h"
#include "save_watcher.h"

namespace strata::test {
namespace {

using Clock = SaveWatcher::Clock;

double secondsBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

void sleepSeconds(double s) { std::this_thread::sleep_for(std::chrono::duration<double>(s)); }

/// waitpid; returns the raw status (-1 when it failed).
int reap(pid_t pid) {
  int status = 0;
  return waitpid(pid, &status, 0) == pid ? status : -1;
}

bool mapLoads(const std::filesystem::path& path, std::string* why) {
  try {
    loadMap(path.string());
    return true;
  } catch (const std::exception& e) {
    *why = e.what();
    return false;
  }
}

/// Ends a program that keeps running after its save (SIGTERM: it saves once more and exits 0).
void finishRun(const SaveTrial& trial, pid_t pid, SaveWatcher& watcher) {
  if (!trial.exits_after_save) {
    EXPECT_TRUE(watcher.waitForRename(trial.timeout_s)) << readText(trial.log);
    kill(pid, SIGTERM);
  }
  const int status = reap(pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << readText(trial.log);
}

/// The checks after kill number `run`; counts its landing.
void checkKill(const SaveTrial& trial, const SaveWatcher& watcher, int run,
               const std::vector<std::uint8_t>& previous, KillCounts* counts) {
  const KillLanding landing = watcher.landing();
  const std::vector<std::uint8_t> now = readFile(trial.target.string());
  const bool unchanged = now == previous;
  std::string why;
  const bool loads = unchanged || mapLoads(trial.target, &why);
  EXPECT_TRUE(loads) << "kill " << run << " (" << landingName(landing)
                     << " the write): the map is neither the previous one nor a complete one: "
                     << why;
  if (landing != KillLanding::kAfter) {
    EXPECT_TRUE(unchanged) << "kill " << run << " landed " << landingName(landing)
                           << " the rename, yet the map changed";
  } else if (trial.saves_differ) {
    EXPECT_FALSE(unchanged) << "kill " << run << " landed after the rename: a new map expected";
  }
  const int temporaries = watcher.temporariesPresent();
  if (landing == KillLanding::kAfter) {
    EXPECT_EQ(temporaries, 0) << "kill " << run << ": the save left or kept a temporary";
  }
  counts->most_temporaries = std::max(counts->most_temporaries, temporaries);
  ++(landing == KillLanding::kBefore   ? counts->before
     : landing == KillLanding::kDuring ? counts->during
                                       : counts->after);
}

/// When the temporary appeared after the start, and how long until the rename.
struct SaveWindow {
  double temporary_s = 0.0;
  double write_s = 0.0;
};

SaveWindow measureSaveWindow(const SaveTrial& trial) {
  SaveWatcher watcher(trial.target);
  const Clock::time_point start = Clock::now();
  const pid_t pid = spawnProgram(trial.program, trial.arg_variants.front(), trial.log);
  SaveWindow window;
  if (pid > 0 && watcher.waitForRename(trial.timeout_s) && watcher.temporaryCreated()) {
    window.temporary_s = secondsBetween(start, *watcher.temporaryCreated());
    window.write_s = secondsBetween(*watcher.temporaryCreated(), *watcher.renamed());
  } else {
    ADD_FAILURE() << "no save seen in the measuring run: " << readText(trial.log);
  }
  if (pid > 0) finishRun(trial, pid, watcher);
  std::printf("[ save window ] temporary %.3f s after the start, renamed %.1f ms later\n",
              window.temporary_s, window.write_s * 1e3);
  return window;
}

/// Write durations seen so far (the measuring run, then each kill that landed after the rename;
/// the watcher reads events while it waits to kill, so their times are exact). The armed delays
/// follow their median, so that they track the machine's load.
class WriteDurations {
 public:
  explicit WriteDurations(double first_s) : samples_s_{first_s} {}
  void add(const SaveWatcher& watcher) {
    if (watcher.temporaryCreated() && watcher.renamed())
      samples_s_.push_back(secondsBetween(*watcher.temporaryCreated(), *watcher.renamed()));
  }
  double median_s() const {
    std::vector<double> sorted = samples_s_;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    return sorted[sorted.size() / 2];
  }

 private:
  std::vector<double> samples_s_;
};

/// Starts run `run`, kills it as killDuringSaves() says; false when it could not start.
bool killOneRun(const SaveTrial& trial, const std::vector<std::string>& args, int run,
                double early_s, double write_s, std::mt19937& rng, SaveWatcher& watcher) {
  watcher.reset();
  const pid_t pid = spawnProgram(trial.program, args, trial.log);
  if (pid <= 0) return false;
  if (run % 5 == 0) {
    sleepSeconds(std::uniform_real_distribution<double>(0.0, early_s)(rng));
  } else {
    EXPECT_TRUE(watcher.waitForTemporary(trial.timeout_s)) << readText(trial.log);
    watcher.watchFor(std::uniform_real_distribution<double>(0.0, write_s)(rng));
  }
  kill(pid, SIGKILL);
  reap(pid);
  watcher.poll(0.0);
  return true;
}

}  // namespace

KillCounts killDuringSaves(const SaveTrial& trial, int kills, unsigned seed) {
  KillCounts counts;
  const SaveWindow window = measureSaveWindow(trial);
  if (window.temporary_s <= 0.0) return counts;
  std::mt19937 rng(seed);
  WriteDurations durations(window.write_s);
  SaveWatcher watcher(trial.target);
  std::vector<std::uint8_t> previous = readFile(trial.target.string());
  std::size_t saved_variant = 0;  // the variant whose map the file holds
  for (int run = 0; run < kills; ++run) {
    // Another variant than the file's, so that a completed save changes the file.
    const std::size_t variant = (saved_variant + 1) % trial.arg_variants.size();
    if (!killOneRun(trial, trial.arg_variants[variant], run, window.temporary_s,
                    durations.median_s(), rng, watcher)) {
      ADD_FAILURE() << "cannot start " << trial.program;
      return counts;
    }
    checkKill(trial, watcher, run, previous, &counts);
    durations.add(watcher);
    if (watcher.landing() == KillLanding::kAfter) saved_variant = variant;
    previous = readFile(trial.target.string());
  }
  std::printf("[ kills ] %d SIGKILLs: %d before the write, %d during, %d after; at most %d "
              "temporaries at once; median write %.1f ms\n",
              kills, counts.before, counts.during, counts.after, counts.most_temporaries,
              durations.median_s() * 1e3);
  watcher.reset();
  const pid_t pid = spawnProgram(trial.program, trial.arg_variants.front(), trial.log);
  if (pid > 0) finishRun(trial, pid, watcher);
  EXPECT_EQ(watcher.temporariesPresent(), 0) << "a completed save removes killed writers' leftovers";
  std::string why;
  EXPECT_TRUE(mapLoads(trial.target, &why)) << why;
  EXPECT_GT(counts.during, 0) << "no kill landed during the write: the test lost its point";
  return counts;
}

}  // namespace strata::test

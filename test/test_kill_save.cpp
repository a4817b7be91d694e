// SIGKILL at random moments of real processes saving a map: `strata fuse --map` and
// strata-mapper's SAVE_MAP, 50 times each. After every kill the map file is the previous one byte
// for byte or a complete new one, and temporaries of killed writers are removed by the next save.
// Where the kills landed (before/during/after the write) is printed from the folder's inotify
// events.
#include <gtest/gtest.h>

#include <filesystem>

#include "kill_trials.h"
#include "lcm_process_helpers.h"
#include "lcm_test_helpers.h"
#include "strata/command_t.hpp"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

constexpr int kKills = 50;

TEST(KillDuringSave, StrataFuseMapIsThePreviousOrACompleteNewOne) {
  const fs::path dir = freshTestDir("kill_fuse");
  SaveTrial trial;
  trial.program = STRATA_CLI_BIN;
  trial.target = dir / "map.strata";
  trial.log = dir / "fuse.log";
  // Two inputs (the analytic scene, 2 cm voxels, a different number of frames) whose maps differ,
  // so a completed save always changes the file.
  for (const char* frames : {"6", "8"}) {
    trial.arg_variants.push_back({"fuse", "--frames", frames, "--voxel-size", "0.02", "--map",
                                  trial.target.string(), "--quiet"});
  }
  const SaveWindow window = measureSaveWindow(trial);
  ASSERT_GT(window.temporary_s, 0.0);
  const KillCounts counts = killDuringSaves(trial, window, kKills, 20261204u);
  EXPECT_GT(counts.during, 0) << "no kill landed during the write: the test lost its point";
  fs::remove_all(dir);
}

/// A log of `frames` frames of the room, then SAVE_MAP (strata-mapper's --map).
void writeSaveLog(const fs::path& path, int frames) {
  const auto session = roomSession(0, frames);
  FrameLogWriter log(path, session->intrinsics());
  for (int i = 0; i < frames; ++i) log.frame(session->load(i), i, 0.1 * i);
  log.command(command_t::SAVE_MAP, 1, 0.1 * frames);
}

TEST(KillDuringSave, StrataMapperMapIsThePreviousOrACompleteNewOne) {
  const fs::path dir = freshTestDir("kill_mapper");
  writeSaveLog(dir / "frames.lcm", 4);
  SaveTrial trial;
  trial.program = STRATA_MAPPER_BIN;
  trial.target = dir / "map.strata";
  trial.log = dir / "mapper.log";
  trial.exits_after_save = false;
  // NOTE: it resumes the previous map each run, so its saves grow it; a map whose fused
  // weights all reached the clamp could save identical bytes, so "differs" is not asserted.
  trial.saves_differ = false;
  // file:// as fast as it reads, a queue that holds the whole log, publishing into memq://:
  // nothing on the network.
  trial.arg_variants.push_back(
      {"--url", "file://" + (dir / "frames.lcm").string() + "?speed=0", "--output-url", "memq://",
       "--map", trial.target.string(), "--no-change", "--queue", "64", "--esdf-rate", "0",
       "--mesh-rate", "0", "--no-keyframe-scores", "--quiet"});
  const SaveWindow window = measureSaveWindow(trial);
  ASSERT_GT(window.temporary_s, 0.0);
  const KillCounts counts = killDuringSaves(trial, window, kKills, 4122026u);
  EXPECT_GT(counts.during, 0) << "no kill landed during the write: the test lost its point";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::test

// SIGKILL at random moments of `strata fuse --map`: after every kill the map file is the previous
// one byte for byte or a complete new one, and temporaries of killed writers are removed by the
// next save. Where the kills landed (before/during/after the write) is printed from the folder's
// inotify events. CI kills 20 times (about 50 s); test_kill_save_long 50 times (about 2 min,
// labelled long). strata-mapper's save: test_kill_mapper.cpp.
#include <gtest/gtest.h>

#include <filesystem>

#include "kill_trials.h"
#include "lcm_process_helpers.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

#ifndef STRATA_KILLS
#define STRATA_KILLS 20
#endif
constexpr int kKills = STRATA_KILLS;

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
  killDuringSaves(trial, kKills, 20261204u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::test

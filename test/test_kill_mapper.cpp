// SIGKILL at random moments of strata-mapper saving its map on SAVE_MAP, 50 times: after every
// kill the map file is the previous one byte for byte or a complete new one, and temporaries of
// killed writers are removed by the next save. Landings before/during/after the write are printed
// (test_kill_save.cpp does the same for `strata fuse --map`).
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
  killDuringSaves(trial, kKills, 4122026u);
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::test

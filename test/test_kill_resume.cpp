// strata-mapper killed (SIGKILL) after a save and restarted with its --map continues from the
// saved map: the end result equals an uninterrupted run over the same frames in the same order.
// Frames come from LCM logs through the file:// provider with a queue that holds them all, so no
// frame is dropped and both runs fuse exactly the same frames (no network, no UDP loss).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "core/atomic_file.h"
#include "lcm_process_helpers.h"
#include "lcm_test_helpers.h"
#include "map/map_file.h"
#include "map_compare.h"
#include "strata/command_t.hpp"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

constexpr int kFrames = 12;      // the whole session
constexpr int kFirstPart = 6;    // fused before the kill
constexpr double kTimeoutS = 120.0;

/// Frames [first, end) of the room's session 0 (kFrames along its path), then SAVE_MAP if asked.
void writePartLog(const fs::path& path, int first, int end, bool save) {
  const auto session = roomSession(0, kFrames);
  FrameLogWriter log(path, session->intrinsics());
  for (int i = first; i < end; ++i) log.frame(session->load(i), i, 0.05 * (i - first));
  if (save) log.command(command_t::SAVE_MAP, 1, 0.05 * (end - first));
}

std::vector<std::string> mapperArgs(const fs::path& log, const fs::path& map) {
  return {"--url", "file://" + log.string() + "?speed=0", "--output-url", "memq://", "--map",
          map.string(), "--no-change", "--queue", "64", "--esdf-rate", "0", "--mesh-rate", "0",
          "--no-keyframe-scores"};
}

bool waitForLine(const fs::path& log, const std::string& line) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(kTimeoutS);
  while (readText(log).find(line) == std::string::npos) {
    if (std::chrono::steady_clock::now() > end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

/// Waits for `pid` after `signal`; returns its exit code (-1 when it did not exit normally).
int stop(pid_t pid, int signal) {
  kill(pid, signal);
  int status = 0;
  if (waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return -1;
  return WEXITSTATUS(status);
}

/// A mapper over `log` until the end of it, then SIGTERM: it fuses what is queued and saves.
MapperSummary runToEnd(const fs::path& log, const fs::path& map, const fs::path& output) {
  const pid_t pid = spawnMapper(mapperArgs(log, map), output);
  EXPECT_GT(pid, 0);
  EXPECT_TRUE(waitForLine(output, "stopped delivering")) << readText(output);
  EXPECT_EQ(stop(pid, SIGTERM), 0) << readText(output);
  return parseMapperSummary(readText(output));
}

TEST(MapperResume, KilledAndRestartedFromItsSavedMapEndsAsAnUninterruptedRun) {
  const fs::path dir = freshTestDir("resume");
  writePartLog(dir / "whole.lcm", 0, kFrames, false);
  writePartLog(dir / "first.lcm", 0, kFirstPart, true);
  writePartLog(dir / "rest.lcm", kFirstPart, kFrames, false);

  EXPECT_EQ(runToEnd(dir / "whole.lcm", dir / "whole.strata", dir / "whole.log").fused, kFrames);

  const fs::path map = dir / "resumed.strata";
  const pid_t first = spawnMapper(mapperArgs(dir / "first.lcm", map), dir / "first.log");
  ASSERT_GT(first, 0);
  ASSERT_TRUE(waitForLine(dir / "first.log", "saved the map")) << readText(dir / "first.log");
  EXPECT_EQ(stop(first, SIGKILL), -1) << "SIGKILL ends it without its exit save";
  const TsdfMap saved = loadMap(map.string());

  const MapperSummary rest = runToEnd(dir / "rest.lcm", map, dir / "rest.log");
  EXPECT_EQ(rest.fused, kFrames - kFirstPart);
  EXPECT_NE(readText(dir / "rest.log").find("resuming from " + map.string()), std::string::npos)
      << readText(dir / "rest.log");

  const TsdfMap whole = loadMap((dir / "whole.strata").string());
  const TsdfMap resumed = loadMap(map.string());
  const MapDifference diff = compareMaps(whole, resumed, 1e-5f, 1e-5f);
  EXPECT_GT(diff.updated_voxels, 10000u);
  EXPECT_EQ(diff.blocks_only_in_a, 0u);
  EXPECT_EQ(diff.blocks_only_in_b, 0u);
  EXPECT_EQ(diff.distance_mismatches, 0u) << "max " << diff.max_distance_difference_m << " m";
  EXPECT_EQ(diff.weight_mismatches, 0u);
  // The second part mattered: the map before it differs from the end result.
  EXPECT_GT(compareMaps(whole, saved, 1e-5f, 1e-5f).weight_mismatches, 1000u);
  fs::remove_all(dir);
}

TEST(MapperResume, ACorruptMapFileIsRefusedAndLeftAsItIs) {
  const fs::path dir = freshTestDir("resume_corrupt");
  writePartLog(dir / "frames.lcm", 0, 2, false);
  const fs::path map = dir / "map.strata";
  const std::string torn = "STRATAMP and then nothing a map file holds";
  writeFileAtomically(map.string(), std::vector<std::uint8_t>(torn.begin(), torn.end()));
  const pid_t pid = spawnMapper(mapperArgs(dir / "frames.lcm", map), dir / "mapper.log");
  ASSERT_GT(pid, 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string log = readText(dir / "mapper.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 2) << log;
  EXPECT_NE(log.find("cannot resume from the map file"), std::string::npos) << log;
  const std::vector<std::uint8_t> after = readFile(map.string());
  EXPECT_EQ(std::string(after.begin(), after.end()), torn) << "the file was overwritten";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::test

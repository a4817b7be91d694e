// strata-mapper killed (SIGKILL) after a save and restarted with its --map continues from the
// saved map: the end result equals an uninterrupted run over the same frames in the same order.
// Twice: frames from LCM logs through the file:// provider (a queue that holds them all: no frame
// dropped, no network), and from strata-play over UDP multicast inside a network namespace of
// its own, with flow control of one frame in flight. With change detection, over three sessions
// killed in the middle one: the static map and the sessions' count end as uninterrupted.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <thread>

#include "strata/core/atomic_file.h"
#include "strata/lcm/channels.h"
#include "lcm_process_helpers.h"
#include "lcm_test_helpers.h"
#include "strata/map/map_file.h"
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

/// A mapper with `args` until the end of its log, then SIGTERM: it fuses what is queued and saves.
MapperSummary runToEnd(const std::vector<std::string>& args, const fs::path& output) {
  const pid_t pid = spawnMapper(args, output);
  EXPECT_GT(pid, 0);
  EXPECT_TRUE(waitForLine(output, "stopped delivering")) << readText(output);
  EXPECT_EQ(stop(pid, SIGTERM), 0) << readText(output);
  return parseMapperSummary(readText(output));
}

/// A mapper with `args` until its first save, then SIGKILL; the file it saved is copied to
/// `saved` (the resumed run goes on to overwrite it).
void killAfterSave(const std::vector<std::string>& args, const fs::path& output,
                   const fs::path& map, const fs::path& saved) {
  const pid_t pid = spawnMapper(args, output);
  ASSERT_GT(pid, 0);
  ASSERT_TRUE(waitForLine(output, "saved the map")) << readText(output);
  EXPECT_EQ(stop(pid, SIGKILL), -1) << "SIGKILL ends it without its exit save";
  fs::copy_file(map, saved);
}

/// The resumed map equals the uninterrupted one voxel for voxel; the map saved before the kill
/// does not (the second part mattered).
void expectResumedEqualsWhole(const fs::path& whole_path, const fs::path& saved_path,
                              const fs::path& resumed_path) {
  const TsdfMap whole = loadMap(whole_path.string());
  const TsdfMap resumed = loadMap(resumed_path.string());
  const MapDifference diff = compareMaps(whole, resumed, 1e-5f, 1e-5f);
  std::printf("[ resume ] %zu observed voxels compared, %zu distance and %zu weight mismatches, "
              "max distance difference %.2g m\n",
              diff.updated_voxels, diff.distance_mismatches, diff.weight_mismatches,
              diff.max_distance_difference_m);
  EXPECT_GT(diff.updated_voxels, 10000u);
  EXPECT_EQ(diff.blocks_only_in_a, 0u);
  EXPECT_EQ(diff.blocks_only_in_b, 0u);
  EXPECT_EQ(diff.distance_mismatches, 0u) << "max " << diff.max_distance_difference_m << " m";
  EXPECT_EQ(diff.weight_mismatches, 0u);
  const TsdfMap saved = loadMap(saved_path.string());
  EXPECT_GT(compareMaps(whole, saved, 1e-5f, 1e-5f).weight_mismatches, 1000u);
}

TEST(MapperResume, KilledAndRestartedFromItsSavedMapEndsAsAnUninterruptedRun) {
  const fs::path dir = freshTestDir("resume");
  writePartLog(dir / "whole.lcm", 0, kFrames, false);
  writePartLog(dir / "first.lcm", 0, kFirstPart, true);
  writePartLog(dir / "rest.lcm", kFirstPart, kFrames, false);

  EXPECT_EQ(
      runToEnd(mapperArgs(dir / "whole.lcm", dir / "whole.strata"), dir / "whole.log").fused,
      kFrames);

  const fs::path map = dir / "resumed.strata";
  ASSERT_NO_FATAL_FAILURE(killAfterSave(mapperArgs(dir / "first.lcm", map), dir / "first.log", map,
                                        dir / "saved.strata"));

  const MapperSummary rest = runToEnd(mapperArgs(dir / "rest.lcm", map), dir / "rest.log");
  EXPECT_EQ(rest.fused, kFrames - kFirstPart);
  EXPECT_NE(readText(dir / "rest.log").find("resuming from " + map.string()), std::string::npos)
      << readText(dir / "rest.log");

  expectResumedEqualsWhole(dir / "whole.strata", dir / "saved.strata", map);
  fs::remove_all(dir);
}

/// Bash (no single quotes) for `unshare --net bash -c`: strata-play sends the room's session to
/// strata-mapper whole; then its first part with a SAVE_MAP, SIGKILL, a mapper restarted on the
/// saved map, the rest. Exit codes to dir/rc.txt, logs beside them.
std::string playResumeScript(const fs::path& dir) {
  const std::string d = dir.string();
  const std::string url = lcm_io::kDefaultUrl;
  std::ostringstream s;
  s << "ip link set lo up && ip route add 224.0.0.0/4 dev lo || exit 10\n"
    << "M=\"" << STRATA_MAPPER_BIN << " --url " << url
    << " --no-change --esdf-rate 0 --mesh-rate 0 --no-keyframe-scores --queue 64\"\n"
    << "P=\"" << STRATA_PLAY_BIN << " sim:room:0 --sim-frames " << kFrames
    << " --rate 0 --window 1 --quiet --mapper-timeout 60 --url " << url << "\"\n"
    << "$M --map " << d << "/whole.strata > " << d << "/whole_mapper.log 2>&1 & MAPPER=$!\n"
    << "$P > " << d << "/whole_play.log 2>&1; R=\"whole_play=$?\"\n"
    << "kill -TERM $MAPPER; wait $MAPPER; R=\"$R whole_mapper=$?\"\n"
    << "$M --map " << d << "/resumed.strata > " << d << "/first_mapper.log 2>&1 & MAPPER=$!\n"
    << "$P --frames " << kFirstPart << " --no-end-session --save " << d << "/resumed.strata > "
    << d << "/first_play.log 2>&1; R=\"$R first_play=$?\"\n"
    << "kill -KILL $MAPPER; wait $MAPPER; R=\"$R first_mapper=$?\"\n"
    << "cp " << d << "/resumed.strata " << d << "/saved.strata\n"
    << "$M --map " << d << "/resumed.strata > " << d << "/rest_mapper.log 2>&1 & MAPPER=$!\n"
    << "$P --first " << kFirstPart << " > " << d << "/rest_play.log 2>&1; R=\"$R rest_play=$?\"\n"
    << "kill -TERM $MAPPER; wait $MAPPER; R=\"$R rest_mapper=$?\"\n"
    << "echo $R > " << d << "/rc.txt\n";
  return s.str();
}

TEST(MapperResume, ReplayedByStrataPlayKilledAndRestartedEndsAsAnUninterruptedRun) {
  if (std::system("unshare --net true > /dev/null 2>&1") != 0) {
    GTEST_SKIP() << "network namespaces are not permitted here ('unshare --net' failed: needs "
                    "root or CAP_SYS_ADMIN); strata-play talks to strata-mapper over UDP "
                    "multicast only inside a namespace of its own";
  }
  const fs::path dir = freshTestDir("resume_play");
  const int rc = std::system(("unshare --net bash -c '" + playResumeScript(dir) + "'").c_str());
  const std::string logs = readText(dir / "first_mapper.log") + readText(dir / "rest_mapper.log");
  ASSERT_EQ(rc, 0) << logs;
  // 137: killed by SIGKILL (128 + 9), so without its exit save.
  EXPECT_EQ(readText(dir / "rc.txt"),
            "whole_play=0 whole_mapper=0 first_play=0 first_mapper=137 rest_play=0 "
            "rest_mapper=0\n")
      << logs;
  EXPECT_EQ(parseMapperSummary(readText(dir / "whole_mapper.log")).fused, kFrames);
  EXPECT_EQ(parseMapperSummary(readText(dir / "rest_mapper.log")).fused, kFrames - kFirstPart);
  EXPECT_NE(readText(dir / "first_mapper.log").find("saved the map (" + std::to_string(kFirstPart)),
            std::string::npos)
      << logs;
  EXPECT_NE(readText(dir / "rest_mapper.log").find("resuming from"), std::string::npos) << logs;
  expectResumedEqualsWhole(dir / "whole.strata", dir / "saved.strata", dir / "resumed.strata");
  fs::remove_all(dir);
}

constexpr int kSessionFrames = 8;  // per session, with change detection
constexpr int kCutFrame = 4;       // of session 1: fused before the kill

/// Sessions [first_session, end_session) of the room, kSessionFrames each, each closed by
/// STOP_SESSION; frames of first_session from `first_frame`, and the log cut before frame
/// `cut_frame` of session `end_session - 1` (-1: no cut) with a SAVE_MAP instead.
void writeSessionsLog(const fs::path& path, int first_session, int first_frame, int end_session,
                      int cut_frame) {
  FrameLogWriter log(path, roomSession(0, kSessionFrames)->intrinsics());
  double t = 0.0;
  std::int64_t request = 1;
  for (int s = first_session; s < end_session; ++s) {
    const auto session = roomSession(s, kSessionFrames);
    const bool cut = s == end_session - 1 && cut_frame >= 0;
    const int begin = s == first_session ? first_frame : 0;
    const int end = cut ? cut_frame : kSessionFrames;
    for (int i = begin; i < end; ++i) log.frame(session->load(i), s * kSessionFrames + i, t += 0.05);
    log.command(cut ? command_t::SAVE_MAP : command_t::STOP_SESSION, request++, t += 0.05);
  }
}

TEST(MapperResume, WithChangeDetectionKilledMidSessionEndsAsAnUninterruptedRun) {
  const fs::path dir = freshTestDir("resume_change");
  writeSessionsLog(dir / "whole.lcm", 0, 0, 3, -1);
  writeSessionsLog(dir / "first.lcm", 0, 0, 2, kCutFrame);
  writeSessionsLog(dir / "rest.lcm", 1, kCutFrame, 3, -1);
  auto args = [](const fs::path& log, const fs::path& map) {
    std::vector<std::string> a = mapperArgs(log, map);
    a.erase(std::find(a.begin(), a.end(), "--no-change"));
    a.push_back("--no-objects");  // the object database resumes from its own file
    return a;
  };
  EXPECT_EQ(runToEnd(args(dir / "whole.lcm", dir / "whole.strata"), dir / "whole.log").fused,
            3 * kSessionFrames);

  const fs::path map = dir / "resumed.strata";
  ASSERT_NO_FATAL_FAILURE(
      killAfterSave(args(dir / "first.lcm", map), dir / "first.log", map, dir / "saved.strata"));
  const MapFileContents saved = loadMapFile((dir / "saved.strata").string());
  ASSERT_TRUE(saved.sessions.has_value()) << "a mapper state (format version 2)";
  EXPECT_EQ(saved.sessions->sessions_ended, 1u);
  EXPECT_TRUE(saved.sessions->session_open);
  EXPECT_EQ(saved.sessions->session_frames, static_cast<std::uint64_t>(kCutFrame));
  ASSERT_TRUE(saved.static_map.has_value());

  const MapperSummary rest = runToEnd(args(dir / "rest.lcm", map), dir / "rest.log");
  EXPECT_EQ(rest.fused, 2 * kSessionFrames - kCutFrame);
  EXPECT_NE(readText(dir / "rest.log").find("1 ended session and session 1 open with " +
                                            std::to_string(kCutFrame) + " frames"),
            std::string::npos)
      << readText(dir / "rest.log");

  const MapFileContents whole = loadMapFile((dir / "whole.strata").string());
  const MapFileContents resumed = loadMapFile(map.string());
  for (const MapFileContents* c : {&whole, &resumed}) {
    ASSERT_TRUE(c->sessions.has_value());
    EXPECT_EQ(c->sessions->sessions_ended, 3u);
    EXPECT_FALSE(c->sessions->session_open);
    EXPECT_EQ(c->sessions->frames, static_cast<std::uint64_t>(3 * kSessionFrames));
  }
  const MapDifference diff = compareMaps(whole.map, resumed.map, 0.0f, 0.0f);
  std::printf("[ resume ] static maps after 3 sessions: %zu observed voxels compared, %zu distance "
              "and %zu weight mismatches\n",
              diff.updated_voxels, diff.distance_mismatches, diff.weight_mismatches);
  EXPECT_GT(diff.updated_voxels, 10000u);
  EXPECT_EQ(diff.blocks_only_in_a + diff.blocks_only_in_b, 0u);
  EXPECT_EQ(diff.distance_mismatches, 0u) << "max " << diff.max_distance_difference_m << " m";
  EXPECT_EQ(diff.weight_mismatches, 0u);
  EXPECT_EQ(diff.color_mismatches, 0u);
  EXPECT_GT(compareMaps(whole.map, *saved.static_map, 1e-5f, 1e-5f).weight_mismatches, 1000u)
      << "the sessions after the kill mattered";
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

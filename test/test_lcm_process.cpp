// strata-play and strata-mapper as separate processes: a replay end to end inside a network
// namespace of its own (nothing leaves the machine), and SIGTERM in the middle of fusion.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <thread>

#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/lcm_time.h"
#include "lcm_process_helpers.h"
#include "lcm_test_helpers.h"
#include "strata/map/map_file.h"
#include "strata/mesh/extract_mesh.h"
#include "strata/sim/session/sim_session.h"
#include "strata/map_stats_t.hpp"
#include "strata/mesh_update_t.hpp"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

TEST(LcmProcesses, PlayerAndMapperReplayASessionInTheirOwnNetworkNamespace) {
  if (const std::string why = namespaceUnavailable(); !why.empty()) GTEST_SKIP() << why;
  constexpr int kFrames = 20;
  const fs::path dir = freshTestDir("processes");
  const std::string script = namespaceReplayScript(dir, kFrames);
  const int rc = std::system(("unshare --net bash -c '" + script + "'").c_str());
  ASSERT_EQ(rc, 0) << "the replay script failed; logs:\n"
                   << readText(dir / "mapper.log") << readText(dir / "play.log");
  EXPECT_EQ(readText(dir / "rc.txt"), "play=0 mapper=0\n") << readText(dir / "mapper.log");

  const RecordedOutputs recorded = readRecordedOutputs(dir / "outputs.lcm");
  ASSERT_FALSE(recorded.stats.empty()) << "lcm-logger recorded no map_stats_t";
  const map_stats_t& last = recorded.stats.back();
  EXPECT_EQ(last.frames_received, kFrames);
  EXPECT_EQ(last.frames_fused, kFrames);
  EXPECT_EQ(last.messages_bad, 0);
  EXPECT_FALSE(last.session_active) << "the player ended the session";
  EXPECT_EQ(recorded.keyframe_scores, static_cast<std::size_t>(kFrames));
  ASSERT_FALSE(recorded.esdf_slices.empty()) << "no ESDF slice recorded";
  std::size_t observed_cells = 0;
  for (int row = 0; row < recorded.esdf_slices.back().height; ++row) {
    for (int col = 0; col < recorded.esdf_slices.back().width; ++col) {
      if (recorded.esdf_slices.back().state[row][col] != 2) continue;
      ++observed_cells;
      EXPECT_TRUE(std::isfinite(recorded.esdf_slices.back().distance_m[row][col]));
    }
  }
  EXPECT_GT(observed_cells, 100u) << "the last ESDF slice shows the mapped room at 1 m";
  ASSERT_GE(recorded.mesh_updates.size(), 2u);
  const TsdfMap map = loadMap((dir / "map.strata").string());  // saved on SIGTERM
  const std::size_t triangles = extractMesh(map).triangles.size();
  EXPECT_GT(triangles, 1000u);
  EXPECT_EQ(viewerTriangles(recorded.mesh_updates), triangles)
      << "the mesh updates received rebuild the saved map's mesh";
  fs::remove_all(dir);
}

TEST(LcmProcesses, SigtermDuringFusionLeavesALoadableMap) {
  constexpr int kEvents = 40;            // frames in the log
  constexpr double kFramePeriodS = 0.1;  // played at real speed: 4 s of frames
  const fs::path dir = freshTestDir("sigterm");
  writeFrameLog(dir / "frames.lcm", kEvents, kFramePeriodS);
  const std::string url = "file://" + (dir / "frames.lcm").string() + "?speed=1";
  const pid_t pid =
      spawnMapper({"--url", url, "--output-url", "memq://", "--map", (dir / "map.strata").string(),
                   "--no-change", "--esdf-rate", "0", "--mesh-rate", "0", "--quiet"},
                  dir / "mapper.log");
  ASSERT_GT(pid, 0);
  // Once it listens (Vulkan is up), 1.5 s into the 4 s of frames: fusion is under way.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (readText(dir / "mapper.log").find("listening on") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string log = readText(dir / "mapper.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 0) << log;
  const MapperSummary summary = parseMapperSummary(log);
  EXPECT_GE(summary.fused, 1) << log;
  EXPECT_LT(summary.received, kEvents) << "SIGTERM came after the log ended: " << log;
  const TsdfMap map = loadMap((dir / "map.strata").string());
  EXPECT_GT(map.blockCount(), 0u);
  for (const auto& entry : fs::directory_iterator(dir)) {
    EXPECT_EQ(entry.path().filename().string().find("map.strata.tmp"), std::string::npos)
        << "temporary left behind: " << entry.path();
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::test

// The live chain in a real browser: strata-play replays a simulated room session's RGB-D frames
// without poses and its grey stereo + IMU, strata-vio tracks the stereo and publishes poses,
// strata-mapper fuses the frames on them, strata-view follows both over LCM, and Debian's headless
// Chromium (test/browser/live_check.cjs) shows it; all in a network namespace of their own (no
// traffic leaves the machine). The page must hold the mapper's last published block count and the
// camera's last pose (strata-vio's last), with no console error. Skips, saying why, without a namespace, Chromium, Node.js or
// web/'s npm packages.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <fstream>

#include <nlohmann/json.hpp>

#include "browser_available.h"
#include "lcm_process_helpers.h"
#include "strata/lcm/channels.h"
#include "strata/lcm/convert_pose.h"
#include "strata/pose_t.hpp"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

TEST(ViewLiveChain, TheBrowserShowsWhatTheMapperPublished) {
  const std::string why = namespaceUnavailable() + browserUnavailable();
  if (!why.empty()) GTEST_SKIP() << why;
  const fs::path dir = freshTestDir("view_live_chain");
  const std::string d = dir.string();
  // 6 s of the room's path at half-size grey stereo (test_vio_chain's session, shorter).
  const std::string sim = std::string(STRATA_CLI_BIN) +
                          " sim --sessions 1 --stereo --stereo-duration 6 --stereo-width 376 "
                          "--stereo-height 240 --frames 50 --quiet --out " + d + "/sim > " + d +
                          "/sim.log 2>&1";
  ASSERT_EQ(std::system(sim.c_str()), 0) << readText(dir / "sim.log");
  const std::string session = d + "/sim/session_0";
  const std::string url = lcm_io::kDefaultUrl;
  std::ostringstream s;
  // The browser first (it retries until strata-view answers): its start is the slowest.
  s << namespacePrologue(dir, "STRATA_MAP_STATS|STRATA_POSE")
    << "node " << STRATA_LIVE_CHECK_SCRIPT << " " << STRATA_WEB_DIR << " http://127.0.0.1:18765/ " << d
    << "/play.done " << d << "/seen.json " << d << "/live.png > " << d << "/browser.log 2>&1 &\n"
    << "BROWSER=$!\n"
    << STRATA_MAPPER_BIN << " --url \"" << url << "\" --map \"\" --no-change --mesh-rate 0 --esdf-rate 2 > "
    << d << "/mapper.log 2>&1 &\n"
    << "MAPPER=$!\n"
    << STRATA_VIO_BIN << " --url \"" << url << "\" --calib " << session << " --max-idle-s 5 --queue 200 > "
    << d << "/vio.log 2>&1 &\n"
    << "VIO=$!\n"
    << STRATA_VIEW_BIN << " --port 18765 --lcm-url \"" << url << "\" > " << d << "/view.log 2>&1 &\n"
    << "VIEW=$!\n"
    << "for i in $(seq 1200); do grep -q \"listening on\" " << d << "/mapper.log && grep -q "
    << "\"listening on\" " << d << "/vio.log && grep -q \"listening on\" " << d << "/view.log && break; sleep 0.1; done\n"
    << STRATA_PLAY_BIN << " " << session << " --with-stereo --no-poses --rate 1 --quiet --url \"" << url
    << "\" --mapper-timeout 120 > " << d << "/play.log 2>&1\n"
    << "PLAY=$?\n"
    << "wait $VIO; VIO_RC=$?\n"
    << "touch " << d << "/play.done\n"
    << "wait $BROWSER; BROWSER_RC=$?\n"
    << "kill -TERM $MAPPER; wait $MAPPER; MAPPER_RC=$?\n"
    << "kill -INT $VIEW; wait $VIEW; VIEW_RC=$?\n"
    << "sleep 0.5; kill -INT $LOGGER; wait $LOGGER\n"
    << "echo play=$PLAY vio=$VIO_RC mapper=$MAPPER_RC view=$VIEW_RC browser=$BROWSER_RC > " << d << "/rc.txt\n";
  const int rc = std::system(("unshare --net bash -c '" + s.str() + "'").c_str());
  ASSERT_EQ(rc, 0) << readText(dir / "browser.log") << readText(dir / "view.log");
  ASSERT_EQ(readText(dir / "rc.txt"), "play=0 vio=0 mapper=0 view=0 browser=0\n")
      << "browser:\n" << readText(dir / "browser.log") << "view:\n" << readText(dir / "view.log")
      << "vio:\n" << readText(dir / "vio.log")
      << "mapper:\n" << readText(dir / "mapper.log") << "play:\n" << readText(dir / "play.log");

  // What the mapper published last, and the camera's last pose (strata-vio's), from the log.
  lcm::LogFile log((dir / "outputs.lcm").string(), "r");
  ASSERT_TRUE(log.good());
  map_stats_t last_stats;
  bool have_stats = false;
  Eigen::Isometry3d last_pose = Eigen::Isometry3d::Identity();
  int poses = 0;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    if (event->channel == lcm_io::kStatsChannel) {
      have_stats = last_stats.decode(event->data, 0, event->datalen) > 0;
    } else if (event->channel == lcm_io::kPoseChannel) {
      pose_t pose;
      if (pose.decode(event->data, 0, event->datalen) > 0) {
        last_pose = lcm_io::decodePose(pose);
        ++poses;
      }
    }
  }
  ASSERT_TRUE(have_stats);
  ASSERT_GT(poses, 20) << "strata-vio published " << poses << " poses";
  EXPECT_GT(last_stats.frames_fused, 5);

  std::ifstream in(dir / "seen.json");
  const nlohmann::json seen = nlohmann::json::parse(in);
  EXPECT_TRUE(seen["consoleErrors"].empty()) << seen["consoleErrors"].dump(1);
  EXPECT_TRUE(seen["pageErrors"].empty()) << seen["pageErrors"].dump(1);
  const auto& state = seen["state"];
  EXPECT_TRUE(state["connected"].get<bool>());
  EXPECT_EQ(state["hello"]["mode"], "live");
  EXPECT_TRUE(state["errors"].empty()) << state["errors"].dump();
  EXPECT_EQ(state["stats"]["blocks"].get<long long>(), last_stats.blocks);
  EXPECT_EQ(state["stats"]["frames"].get<long long>(), last_stats.frames_fused);
  EXPECT_GT(state["trajectoryPoints"].get<int>(), 20) << "the page drew no VIO trajectory";
  EXPECT_GT(state["meshes"].get<int>(), 50) << "the page shows almost no mesh blocks";
  ASSERT_TRUE(state["lastPose"].is_object());
  const auto& T = state["lastPose"]["T_W_C"];
  ASSERT_EQ(T.size(), 16u);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(T[4 * r + c].get<double>(), last_pose.matrix()(r, c), 1e-6) << r << "," << c;
  }
  std::printf("live chain: %lld blocks, %d mesh items on the page; mapper publish to page draw: median %.0f ms, p95 %.0f ms over %d updates\n",
              static_cast<long long>(last_stats.blocks), state["meshes"].get<int>(),
              state["latency_ms"]["p50"].is_number() ? state["latency_ms"]["p50"].get<double>() : -1.0,
              state["latency_ms"]["p95"].is_number() ? state["latency_ms"]["p95"].get<double>() : -1.0,
              state["latency_ms"]["n"].get<int>());
}

}  // namespace
}  // namespace strata::test

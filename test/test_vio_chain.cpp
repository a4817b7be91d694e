// The robot chain without truth poses, as three processes in a network namespace of their own
// (nothing leaves the machine): strata-play sends a `strata sim --stereo` session's RGB-D frames
// without poses and its grey stereo + IMU; strata-vio tracks the grey stream and publishes poses;
// strata-mapper fuses the RGB-D frames at the poses it interpolates from them. Measured: the
// share of frames with a pose after initialisation, the poses' error against the session's truth
// after SE(3) alignment (at their own stamps, and interpolated at the RGB-D frames as the mapper
// fuses them), and what the mapper fused. Also: strata-vio stops cleanly on SIGTERM with its
// summary, and refuses a folder without calibration. Timing is not asserted.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "cli/odometry_summary.h"
#include "strata/io/euroc_dataset.h"
#include "strata/io/tum_format.h"
#include "strata/lcm/channels.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/pose_buffer.h"
#include "lcm_process_helpers.h"
#include "strata/map/map_file.h"
#include "strata/imu_t.hpp"
#include "strata/map_stats_t.hpp"
#include "strata/pose_t.hpp"
#include "test_utils.h"
#include "strata/trajectory/trajectory_error.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

/// Bash (no single quotes) for `unshare --net bash -c`: loopback with multicast, lcm-logger
/// recording poses, IMU and map stats, strata-mapper and strata-vio started and awaited until
/// they listen, strata-play of `session` at `rate`, then the VIO left to finish (--max-idle-s)
/// and the mapper stopped by SIGTERM (it saves its map); exit codes to dir/rc.txt. The VIO's
/// queue holds every frame, so a busy machine delays its poses rather than dropping frames.
std::string chainScript(const fs::path& dir, const fs::path& session, double rate) {
  const std::string d = dir.string();
  const std::string url = lcm_io::kDefaultUrl;
  std::ostringstream s;
  s << namespacePrologue(dir, "STRATA_POSE|STRATA_IMU|STRATA_MAP_STATS") << STRATA_MAPPER_BIN
    << " --url \"" << url << "\" --map " << d
    << "/map.strata --no-change --esdf-rate 0 --no-keyframe-scores > " << d
    << "/mapper.log 2>&1 &\n"
    << "MAPPER=$!\n"
    << STRATA_VIO_BIN << " --url \"" << url << "\" --calib " << session.string() << " --summary "
    << d << "/vio.json --max-idle-s 3 --status-period 2 --queue 200 > " << d << "/vio.log 2>&1 &\n"
    << "VIO=$!\n"
    << "for i in $(seq 1200); do grep -q \"listening on\" " << d << "/mapper.log && grep -q "
    << "\"listening on\" " << d << "/vio.log && break; sleep 0.1; done\n"
    << STRATA_PLAY_BIN << " " << session.string() << " --with-stereo --no-poses --rate " << rate
    << " --quiet --url \"" << url << "\" --mapper-timeout 60 > " << d << "/play.log 2>&1\n"
    << "PLAY=$?\n"
    << "wait $VIO; VIO_RC=$?\n"
    << "kill -TERM $MAPPER; wait $MAPPER; MAPPER_RC=$?\n"
    << "sleep 0.5; kill -INT $LOGGER; wait $LOGGER\n"
    << "echo play=$PLAY vio=$VIO_RC mapper=$MAPPER_RC > " << d << "/rc.txt\n";
  return s.str();
}

struct Recorded {
  std::vector<std::pair<std::int64_t, Eigen::Isometry3d>> poses;  // utime, T_W_C
  std::int64_t first_imu_utime = -1;
  std::size_t imu = 0;
  std::vector<map_stats_t> stats;
};

Recorded readRecorded(const fs::path& path) {
  Recorded r;
  lcm::LogFile log(path.string(), "r");
  if (!log.good()) return r;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    if (event->channel == lcm_io::kPoseChannel) {
      pose_t pose;
      if (pose.decode(event->data, 0, event->datalen) > 0)
        r.poses.emplace_back(pose.utime, lcm_io::decodePose(pose));
    } else if (event->channel == lcm_io::kImuChannel) {
      imu_t imu;
      if (imu.decode(event->data, 0, event->datalen) > 0 && r.imu++ == 0)
        r.first_imu_utime = imu.utime;
    } else if (event->channel == lcm_io::kStatsChannel) {
      map_stats_t stats;
      if (stats.decode(event->data, 0, event->datalen) > 0) r.stats.push_back(stats);
    }
  }
  return r;
}

/// An integer field of strata-vio's flat JSON summary (-1 when absent).
long long jsonInt(const std::string& json, const std::string& key) {
  const std::size_t at = json.find("\"" + key + "\": ");
  if (at == std::string::npos) return -1;
  return std::atoll(json.c_str() + at + key.size() + 4);
}

std::string logs(const fs::path& dir) {
  return "play:\n" + readText(dir / "play.log") + "vio:\n" + readText(dir / "vio.log") +
         "mapper:\n" + readText(dir / "mapper.log");
}

TEST(VioChain, PlayerVioAndMapperFuseASimulatedSessionWithoutTruthPoses) {
  if (const std::string why = namespaceUnavailable(); !why.empty()) GTEST_SKIP() << why;
  const fs::path dir = freshTestDir("vio_chain");
  // 8 s of the room's path: 161 grey pairs at 20 Hz, 24 of the 66 RGB-D frames (3 Hz). Grey
  // images at half the default size render 3x faster; the VIO's error grows from 4 to 7 mm.
  const std::string sim = std::string(STRATA_CLI_BIN) +
                          " sim --sessions 1 --stereo --stereo-duration 8 --stereo-width 376 "
                          "--stereo-height 240 --frames 66 --quiet --out " +
                          (dir / "sim").string() + " > " + (dir / "sim.log").string() + " 2>&1";
  ASSERT_EQ(std::system(sim.c_str()), 0) << readText(dir / "sim.log");
  const fs::path session = dir / "sim" / "session_0";
  const int rc =
      std::system(("unshare --net bash -c '" + chainScript(dir, session, 1.0) + "'").c_str());
  ASSERT_EQ(rc, 0) << logs(dir);
  ASSERT_EQ(readText(dir / "rc.txt"), "play=0 vio=0 mapper=0\n") << logs(dir);

  const euroc::EurocDataset grey = euroc::EurocDataset::open(session.string());
  const std::vector<trajectory::StampedPose> rgbd_truth =
      tum::readTrajectory((session / "groundtruth.txt").string());
  const Recorded r = readRecorded(dir / "outputs.lcm");
  ASSERT_EQ(r.imu, grey.imu().size()) << "lcm-logger missed IMU samples";
  ASSERT_FALSE(r.poses.empty()) << logs(dir);
  // Both streams were restamped with one offset from the first RGB-D frame (t = 0 here), and
  // the first IMU sample sent is the recording's first.
  const double t0_s = rgbd_truth.front().timestamp_s;
  ASSERT_GE(1e-9 * static_cast<double>(grey.imu().front().timestamp_ns), t0_s);
  const std::int64_t base_utime =
      r.first_imu_utime - (grey.imu().front().timestamp_ns - std::llround(t0_s * 1e9)) / 1000;
  const auto trajectoryTime = [&](std::int64_t utime) {
    return t0_s + 1e-6 * static_cast<double>(utime - base_utime);
  };

  // Most frames after initialisation have a pose.
  const double first_pose_s = trajectoryTime(r.poses.front().first);
  std::size_t frames_after = 0;
  for (const auto& f : grey.frames()) frames_after += 1e-9 * f.timestamp_ns >= first_pose_s - 1e-6;
  EXPECT_GE(r.poses.size(), frames_after * 95 / 100)
      << r.poses.size() << " poses for " << frames_after << " frames after the first";
  const std::string summary = readText(dir / "vio.json");
  EXPECT_EQ(jsonInt(summary, "frames_received"), static_cast<long long>(grey.frames().size()));
  EXPECT_EQ(jsonInt(summary, "poses_published"), static_cast<long long>(r.poses.size()));
  EXPECT_EQ(jsonInt(summary, "frames_tracked"), static_cast<long long>(r.poses.size()));
  EXPECT_EQ(jsonInt(summary, "failures"), 0) << summary;

  // Error of the poses at their own stamps against cam0's truth, after SE(3) alignment.
  std::vector<trajectory::StampedPose> estimate;
  lcm_io::PoseBuffer buffer;
  for (const auto& [utime, T_W_C] : r.poses) {
    estimate.push_back({trajectoryTime(utime), T_W_C});
    buffer.add(utime, T_W_C);
  }
  trajectory::TrajectoryErrorOptions exact;
  exact.max_time_difference_s = 1e-4;
  const trajectory::TrajectoryError own =
      trajectory::evaluateTrajectory(estimate, apps::cameraTruth(grey), exact);
  EXPECT_EQ(own.matched, r.poses.size());
  EXPECT_LT(own.ate_rmse_m, 0.03);
  EXPECT_LT(own.ate_max_m, 0.06);
  // The poses the mapper fuses the RGB-D frames at: interpolated as it does, against
  // groundtruth.txt.
  std::vector<trajectory::StampedPose> at_rgbd;
  for (const trajectory::StampedPose& truth : rgbd_truth) {
    const std::int64_t utime = base_utime + std::llround((truth.timestamp_s - t0_s) * 1e6);
    Eigen::Isometry3d T_W_C;
    if (buffer.lookup(utime, &T_W_C) == lcm_io::PoseLookup::kFound)
      at_rgbd.push_back({truth.timestamp_s, T_W_C});
  }
  ASSERT_GE(at_rgbd.size(), 10u);
  const trajectory::TrajectoryError fused = trajectory::evaluateTrajectory(at_rgbd, rgbd_truth, exact);
  EXPECT_LT(fused.ate_rmse_m, 0.03);
  std::printf(
      "strata-vio over LCM: %zu poses for %zu grey frames (%zu after the first pose); ATE "
      "SE(3) at their stamps: RMSE %.4f m, max %.4f m over %.2f m; interpolated at %zu "
      "RGB-D frames: RMSE %.4f m, max %.4f m\n",
      r.poses.size(), grey.frames().size(), frames_after, own.ate_rmse_m, own.ate_max_m,
      own.path_length_m, fused.matched, fused.ate_rmse_m, fused.ate_max_m);

  // The mapper fused the RGB-D frames that have poses; the others were counted, not fused.
  ASSERT_FALSE(r.stats.empty()) << "lcm-logger recorded no map_stats_t";
  const map_stats_t& last = r.stats.back();
  EXPECT_EQ(last.messages_bad, 0);
  EXPECT_EQ(last.frames_rejected, 0);
  EXPECT_EQ(last.frames_fused + last.frames_dropped_no_pose + last.frames_dropped_backlog,
            last.frames_received);
  EXPECT_GE(last.frames_fused, static_cast<std::int64_t>(at_rgbd.size()) - 1)
      << "frames within the poses' span are fused";
  std::printf("strata-mapper: %lld RGB-D frames received, %lld fused, %lld without a pose\n",
              static_cast<long long>(last.frames_received),
              static_cast<long long>(last.frames_fused),
              static_cast<long long>(last.frames_dropped_no_pose));
  EXPECT_GT(loadMap((dir / "map.strata").string()).blockCount(), 100u);
  fs::remove_all(dir);
}

TEST(VioProcess, SigtermStopsItCleanlyWithItsSummaryAndABadCalibrationIsRefused) {
  STRATA_REQUIRE_DATA("euroc_v101_micro", calib);
  const fs::path dir = freshTestDir("vio_sigterm");
  const pid_t pid = spawnProgram(STRATA_VIO_BIN,
                                 {"--url", "memq://", "--calib", calib, "--summary",
                                  (dir / "vio.json").string(), "--status-period", "0.2"},
                                 dir / "vio.log");
  ASSERT_GT(pid, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
  while (readText(dir / "vio.log").find("frames/s") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_EQ(kill(pid, SIGTERM), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  const std::string log = readText(dir / "vio.log");
  ASSERT_TRUE(WIFEXITED(status)) << log;
  EXPECT_EQ(WEXITSTATUS(status), 0) << log;
  EXPECT_NE(log.find("0 frames in, 0 tracked"), std::string::npos) << "a progress line: " << log;
  const std::string summary = readText(dir / "vio.json");
  EXPECT_NE(summary.find("\"stopped_by\": \"signal\""), std::string::npos) << summary;
  EXPECT_EQ(jsonInt(summary, "frames_received"), 0);

  // A folder without the sensor.yaml files: exit 2, the file named.
  const pid_t bad =
      spawnProgram(STRATA_VIO_BIN, {"--url", "memq://", "--calib", dir.string()}, dir / "bad.log");
  ASSERT_GT(bad, 0);
  ASSERT_EQ(waitpid(bad, &status, 0), bad);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(readText(dir / "bad.log").find("sensor.yaml"), std::string::npos)
      << readText(dir / "bad.log");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::test

// Simulated sessions as datasets, `strata sim` output, and the multi-session demo.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include "cli/demo_command.h"
#include "cli/sim_command.h"
#include "strata/io/open_dataset.h"
#include "strata/io/odometry_frame_file.h"
#include "strata/io/tum_format.h"
#include "strata/sim/sensors/odometry_frame.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata::sim {
namespace {

namespace fs = std::filesystem;

std::string readFileText(const fs::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::shared_ptr<const World> loadShipped(const std::string& name) {
  return std::make_shared<const World>(World::load(findWorld(name)));
}

SimSessionConfig smallConfig(int frames) {
  SimSessionConfig config;
  config.max_frames = frames;
  return config;
}

TEST(SimSession, PathsStayClearOfEverySurfaceInEveryShippedWorld) {
  for (const std::string name : {"room", "office", "warehouse", "deadend"}) {
    const auto world = loadShipped(name);
    for (int s = 0; s < world->sessionCount(); ++s) {
      const SimSessionDataset session(world, s, smallConfig(0));
      ASSERT_GT(session.size(), 30u) << name;
      for (const Eigen::Isometry3d& T_W_C : session.truePoses()) {
        const Eigen::Vector3f p = T_W_C.translation().cast<float>();
        ASSERT_GT(session.scene().signedDistance(p), 0.1f)
            << name << " session " << s << " camera at " << p.transpose();
      }
    }
  }
}

TEST(SimSession, ViewsTurnAtAHandHeldRateInEveryShippedWorld) {
  // A hand-held camera turns at tens of degrees per second; the office's paths once flipped by
  // up to 180 degrees in milliseconds where the look-at target switched sides of the path.
  for (const std::string name : {"room", "office", "warehouse", "deadend"}) {
    const auto world = loadShipped(name);
    for (int s = 0; s < world->sessionCount(); ++s) {
      const SimSessionDataset session(world, s, smallConfig(0));
      const Trajectory& trajectory = session.trajectory();
      double fastest_deg_s = 0.0;
      for (double t = 0.0; t < trajectory.duration_s(); t += 0.005) {
        fastest_deg_s = std::max(fastest_deg_s,
                                 trajectory.state(t).angular_velocity_C.norm() * 180.0 / M_PI);
      }
      EXPECT_LT(fastest_deg_s, 120.0) << name << " session " << s;
    }
  }
}

TEST(SimSession, SameSeedSameFramesOtherSeedOtherNoise) {
  const auto world = loadShipped("room");
  SimSessionConfig config = smallConfig(3);
  const SimSessionDataset a(world, 0, config);
  const SimSessionDataset b(world, 0, config);
  config.seed = 12345;
  const SimSessionDataset c(world, 0, config);
  const RgbdFrame fa = a.load(1), fb = b.load(1), fc = c.load(1);
  EXPECT_EQ(fa.depth.depth_m, fb.depth.depth_m);
  EXPECT_EQ(fa.color.rgb, fb.color.rgb);
  EXPECT_TRUE(fa.T_W_C.isApprox(fb.T_W_C));
  EXPECT_NE(fa.depth.depth_m, fc.depth.depth_m);
}

TEST(SimSession, FramesAreValidAndDriftOnlyTouchesTheGivenPoses) {
  const auto world = loadShipped("room");
  SimSessionConfig config = smallConfig(20);
  config.drift = true;
  const SimSessionDataset session(world, 2, config);
  const RgbdFrame frame = session.load(5);
  EXPECT_NO_THROW(validateFrame(frame, session.intrinsics()));
  EXPECT_TRUE(frame.T_W_C.isApprox(session.givenPoses()[5]));
  const double drift_m =
      (session.givenPoses().back().translation() - session.truePoses().back().translation())
          .norm();
  EXPECT_GT(drift_m, 0.0);
  EXPECT_LT(drift_m, 0.5);
  EXPECT_THROW(session.load(session.size()), InputError);
}

TEST(SimSession, ReplacedPosesDropFramesWithoutOneAndKeepEachFramesNoise) {
  const auto world = loadShipped("room");
  SimSessionDataset session(world, 1, smallConfig(6));
  const RgbdFrame before = session.load(3);
  const std::vector<Eigen::Isometry3d> truth = session.truePoses();
  const double t3 = session.timestamp(3);
  Eigen::Isometry3d shifted = truth[3];
  shifted.translation().x() += 0.1;
  std::vector<std::optional<Eigen::Isometry3d>> poses(6);
  poses[2] = truth[2];
  poses[3] = shifted;
  poses[5] = truth[5];
  EXPECT_THROW(session.replaceGivenPoses({}), InputError);
  session.replaceGivenPoses(poses);
  ASSERT_EQ(session.size(), 3u);
  ASSERT_EQ(session.truePoses().size(), 3u);
  ASSERT_EQ(session.givenPoses().size(), 3u);
  const RgbdFrame after = session.load(1);
  EXPECT_EQ(after.depth.depth_m, before.depth.depth_m) << "the same frame draws the same noise";
  EXPECT_TRUE(after.T_W_C.isApprox(shifted));
  EXPECT_TRUE(session.truePoses()[1].isApprox(truth[3]));
  EXPECT_EQ(session.timestamp(1), t3);
  EXPECT_THROW(session.load(3), InputError);
}

TEST(SimCommand, WritesReadableTumSessionsWithGroundTruthAndImu) {
  const fs::path out =
      fs::temp_directory_path() / ("strata_sim_command_test_" + std::to_string(::getpid()));
  fs::remove_all(out);
  apps::SimOptions options;
  options.sessions = 2;
  options.max_frames = 4;
  options.out_dir = out.string();
  options.drift = true;
  options.quiet = true;
  ASSERT_EQ(apps::runSim(options), 0);
  for (const std::string session : {"session_0", "session_1"}) {
    const auto dataset = openDataset((out / session).string());
    EXPECT_EQ(dataset->size(), 4u);
    EXPECT_FALSE(dataset->load(0).color.empty());
    EXPECT_TRUE(fs::exists(out / session / "odometry.txt"));
    std::ifstream imu(out / session / "imu0" / "data.csv");
    std::string header;
    std::getline(imu, header);
    EXPECT_EQ(header.rfind("#timestamp [ns]", 0), 0u) << header;
  }
  EXPECT_TRUE(fs::exists(out / "ground_truth" / "session_1" / "objects.json"));
  EXPECT_TRUE(fs::exists(out / "ground_truth" / "session_1" / "world.ply"));
  fs::remove_all(out);
}

TEST(SimCommand, OwnFramesPutEachSessionsOdometryInAFrameOfItsOwn) {
  const fs::path out =
      fs::temp_directory_path() / ("strata_sim_own_frames_test_" + std::to_string(::getpid()));
  fs::remove_all(out);
  apps::SimOptions options;
  options.sessions = 2;
  options.max_frames = 4;
  options.out_dir = (out / "a").string();
  options.own_frames = true;  // implies drift
  options.quiet = true;
  testing::internal::CaptureStdout();
  ASSERT_EQ(apps::runSim(options), 0);
  options.out_dir = (out / "b").string();
  ASSERT_EQ(apps::runSim(options), 0);
  testing::internal::GetCapturedStdout();

  const auto world = loadShipped("room");
  SimSessionConfig config = smallConfig(4);
  config.drift = true;
  std::vector<Eigen::Isometry3d> frames;
  for (int s = 0; s < 2; ++s) {
    const fs::path dir = out / "a" / ("session_" + std::to_string(s));
    const SimSessionDataset session(world, s, config);
    const Eigen::Isometry3d T_W_S = readOdometryFrame((dir / "odometry_frame.txt").string());
    EXPECT_TRUE(T_W_S.isApprox(randomOdometryFrame({}, session.seed()), 1e-8));
    const std::vector<tum::TimedPose> odometry =
        tum::readTrajectory((dir / "odometry.txt").string());
    ASSERT_EQ(odometry.size(), session.size());
    for (std::size_t i = 0; i < odometry.size(); ++i) {
      const Eigen::Isometry3d expected = T_W_S.inverse() * session.givenPoses()[i];
      EXPECT_LT((odometry[i].T_W_C.matrix() - expected.matrix()).cwiseAbs().maxCoeff(), 1e-8);
    }
    EXPECT_EQ(readFileText(dir / "odometry.txt"),
              readFileText(out / "b" / ("session_" + std::to_string(s)) / "odometry.txt"));
    frames.push_back(T_W_S);
  }
  EXPECT_GT((frames[0].matrix() - frames[1].matrix()).cwiseAbs().maxCoeff(), 0.1);
  fs::remove_all(out);
}

TEST(SimCommand, MalformedWorldFileFailsWithItsLine) {
  const fs::path path =
      fs::temp_directory_path() / ("strata_bad_world_" + std::to_string(::getpid()) + ".yaml");
  std::ofstream(path) << "name: bad\nseed: 1\nrooms:\n  - {name: r, min: [0, 0], max: [4]}\n";
  apps::SimOptions options;
  options.world = path.string();
  options.out_dir =
      (fs::temp_directory_path() / ("strata_bad_world_out_" + std::to_string(::getpid()))).string();
  options.quiet = true;
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runSim(options), 2);
  const std::string message = testing::internal::GetCapturedStderr();
  EXPECT_NE(message.find(":4:"), std::string::npos) << message;
  fs::remove(path);
}

TEST(Demo, RunsTwoSessionsAndWritesTheReport) {
  const fs::path out =
      fs::temp_directory_path() / ("strata_demo_test_" + std::to_string(::getpid()));
  fs::remove_all(out);
  apps::DemoOptions options;
  options.sessions = 2;
  options.frames = 6;
  options.voxel_size_m = 0.05f;
  options.out_dir = out.string();
  options.quiet = true;
  testing::internal::CaptureStdout();
  ASSERT_EQ(apps::runDemo(options), 0);
  const std::string summary = testing::internal::GetCapturedStdout();
  EXPECT_NE(summary.find("Session 1 changed objects"), std::string::npos) << summary;
  EXPECT_TRUE(fs::exists(out / "report.json"));
  EXPECT_TRUE(fs::exists(out / "session_1_mesh.ply"));
  EXPECT_TRUE(fs::exists(out / "session_1_view.png"));
  fs::remove_all(out);
}

}  // namespace
}  // namespace strata::sim

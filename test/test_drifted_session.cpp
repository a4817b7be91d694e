// Sessions in an odometry frame of their own: the random frame, a recorded slice written as a
// drifting session (`strata drift`), and the option that says so to `strata diff`.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "cli/diff_command.h"
#include "cli/drift_command.h"
#include "strata/core/error.h"
#include "strata/io/open_dataset.h"
#include "strata/io/odometry_frame_file.h"
#include "strata/io/tum_format.h"
#include "strata/io/tum_writer.h"
#include "strata/sim/session/drifted_session.h"
#include "test_utils.h"

namespace strata::sim {
namespace {

namespace fs = std::filesystem;

double maxPoseDifference(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  return (a.matrix() - b.matrix()).cwiseAbs().maxCoeff();
}

std::vector<Eigen::Isometry3d> posesOf(const std::vector<tum::TimedPose>& timed) {
  std::vector<Eigen::Isometry3d> poses;
  for (const tum::TimedPose& p : timed) poses.push_back(p.T_W_C);
  return poses;
}

std::string fileText(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

class DriftedSessionTest : public testing::Test {
 protected:
  void SetUp() override {
    const auto* info = testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("strata_test_drifted_" + std::string(info->name()) + "_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A small TUM folder of `count` frames 0.1 m apart along x.
  std::string writeSmallSource(int count) {
    CameraIntrinsics k;
    k.width_px = 8;
    k.height_px = 6;
    k.fx_px = k.fy_px = 8.0f;
    k.cx_px = 3.5f;
    k.cy_px = 2.5f;
    std::vector<RgbdFrame> frames(count);
    for (int i = 0; i < count; ++i) {
      frames[i].timestamp_s = i / 30.0;
      frames[i].depth = DepthImage(8, 6, 1.0f + 0.1f * i);
      frames[i].T_W_C.translation() = Eigen::Vector3d(0.1 * i, 0.0, 1.4);
    }
    writeTumDataset((dir_ / "source").string(), k, frames);
    return (dir_ / "source").string();
  }

  fs::path dir_;
};

TEST(OdometryFrame, GravityAlignedInTheBoxAndSeeded) {
  const OdometryFrameConfig config;
  const Eigen::Isometry3d a = randomOdometryFrame(config, 7);
  EXPECT_TRUE(a.isApprox(randomOdometryFrame(config, 7), 0.0));
  EXPECT_GT(maxPoseDifference(a, randomOdometryFrame(config, 8)), 0.1);
  double max_yaw_rad = 0.0;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const Eigen::Isometry3d T_W_S = randomOdometryFrame(config, seed);
    EXPECT_NEAR(T_W_S.linear()(2, 2), 1.0, 1e-12);  // no roll or pitch
    EXPECT_LE(T_W_S.translation().head<2>().cwiseAbs().maxCoeff(), config.horizontal_offset_m);
    EXPECT_LE(std::abs(T_W_S.translation().z()), config.vertical_offset_m);
    max_yaw_rad =
        std::max(max_yaw_rad, std::abs(std::atan2(T_W_S.linear()(1, 0), T_W_S.linear()(0, 0))));
  }
  EXPECT_GT(max_yaw_rad, 2.5);  // the whole circle is drawn
  OdometryFrameConfig bad;
  bad.vertical_offset_m = -1.0;
  EXPECT_THROW(randomOdometryFrame(bad, 1), InputError);
}

TEST(DriftedSessionRedkitchen, SliceOpensWithTheSourceImagesAndOffsetDriftedOdometry) {
  STRATA_REQUIRE_DATA("redkitchen", source);
  const fs::path out =
      fs::temp_directory_path() / ("strata_test_drift_redkitchen_" + std::to_string(::getpid()));
  fs::remove_all(out);
  DriftedSessionConfig config;
  config.first_frame = 75;
  config.last_frame = 149;
  config.seed = 3;
  const DriftedSession written = writeDriftedSession(source, out.string(), config);
  EXPECT_EQ(written.frames, 75u);
  EXPECT_EQ(written.frames_dropped, 0u);

  const auto slice = openDataset(out.string());
  const auto whole = openDataset(source);
  ASSERT_EQ(slice->size(), 75u);
  EXPECT_EQ(slice->intrinsics().fx_px, whole->intrinsics().fx_px);
  for (std::size_t i : {std::size_t{0}, std::size_t{40}, std::size_t{74}}) {
    const RgbdFrame mine = slice->load(i), theirs = whole->load(75 + i);
    EXPECT_TRUE(fs::equivalent(mine.name, theirs.name)) << mine.name << " vs " << theirs.name;
    EXPECT_TRUE(mine.depth.depth_m == theirs.depth.depth_m) << i;
    EXPECT_TRUE(mine.color.rgb == theirs.color.rgb) << i;
    EXPECT_LT(maxPoseDifference(mine.T_W_C, theirs.T_W_C), 1e-6) << i;
  }

  const Eigen::Isometry3d T_W_S = readOdometryFrame((out / "odometry_frame.txt").string());
  EXPECT_LT(maxPoseDifference(T_W_S, written.T_W_S), 1e-8);
  EXPECT_GT(T_W_S.translation().norm(), 1e-3);
  const auto truth = posesOf(tum::readTrajectory((out / "groundtruth.txt").string()));
  const auto odometry = posesOf(tum::readTrajectory((out / "odometry.txt").string()));
  ASSERT_EQ(odometry.size(), truth.size());
  EXPECT_LT(maxPoseDifference(T_W_S * odometry.front(), truth.front()), 1e-8);
  const auto drifted = addOdometryDrift(truth, config.drift, config.seed);
  double drift_m = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i) {
    EXPECT_LT(maxPoseDifference(odometry[i], T_W_S.inverse() * drifted[i]), 1e-8) << i;
    drift_m =
        std::max(drift_m, ((T_W_S * odometry[i]).translation() - truth[i].translation()).norm());
  }
  EXPECT_GT(drift_m, 1e-4);  // drifted ...
  EXPECT_LT(drift_m, 0.1);   // ... by odometry's amount over ~1 m of path
  fs::remove_all(out);
}

TEST_F(DriftedSessionTest, SameSeedSameFilesAndNoOffsetKeepsTheWorldFrame) {
  const std::string source = writeSmallSource(10);
  DriftedSessionConfig config;
  config.first_frame = 2;
  config.last_frame = 7;
  writeDriftedSession(source, (dir_ / "a").string(), config);
  writeDriftedSession(source, (dir_ / "b").string(), config);
  for (const char* file : {"depth.txt", "rgb.txt", "groundtruth.txt", "odometry.txt",
                           "odometry_frame.txt", "camera.yaml"}) {
    EXPECT_EQ(fileText(dir_ / "a" / file), fileText(dir_ / "b" / file)) << file;
  }
  EXPECT_EQ(openDataset((dir_ / "a").string())->size(), 6u);
  config.seed = 2;
  writeDriftedSession(source, (dir_ / "c").string(), config);
  EXPECT_NE(fileText(dir_ / "a" / "odometry_frame.txt"),
            fileText(dir_ / "c" / "odometry_frame.txt"));
  config.offset = false;
  const DriftedSession plain = writeDriftedSession(source, (dir_ / "d").string(), config);
  EXPECT_TRUE(plain.T_W_S.isApprox(Eigen::Isometry3d::Identity()));
  const auto odometry = posesOf(tum::readTrajectory((dir_ / "d" / "odometry.txt").string()));
  const auto truth = posesOf(tum::readTrajectory((dir_ / "d" / "groundtruth.txt").string()));
  EXPECT_LT(maxPoseDifference(odometry.front(), truth.front()), 1e-9);
}

TEST_F(DriftedSessionTest, BadArgumentsAreRefused) {
  const std::string source = writeSmallSource(5);
  const std::string before = fileText(fs::path(source) / "groundtruth.txt");
  DriftedSessionConfig config;
  config.first_frame = 3;
  config.last_frame = 1;
  EXPECT_THROW(writeDriftedSession(source, (dir_ / "out").string(), config), InputError);
  config.first_frame = 5;
  config.last_frame.reset();
  EXPECT_THROW(writeDriftedSession(source, (dir_ / "out").string(), config), InputError);
  config.first_frame = 0;
  EXPECT_THROW(writeDriftedSession(source, source, config), InputError);  // its own source
  EXPECT_EQ(fileText(fs::path(source) / "groundtruth.txt"), before);
  EXPECT_THROW(writeDriftedSession((dir_ / "nope").string(), (dir_ / "out").string(), config),
               InputError);

  apps::DriftOptions options;
  options.source_dir = source;
  options.out_dir = (dir_ / "cli").string();
  options.first_frame = 4;
  options.last_frame = 2;
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runDrift(options), 2);
  options.first_frame = 9;
  options.last_frame = -1;
  EXPECT_EQ(apps::runDrift(options), 2);
  options.source_dir = (dir_ / "nope").string();
  EXPECT_EQ(apps::runDrift(options), 2);
  const std::string messages = testing::internal::GetCapturedStderr();
  EXPECT_NE(messages.find("first_frame 4 is after last_frame 2"), std::string::npos) << messages;
  EXPECT_NE(messages.find("is beyond its 5 frames"), std::string::npos) << messages;
  EXPECT_NE(messages.find("nope: no such folder"), std::string::npos) << messages;
  options.source_dir = source;
  options.first_frame = 1;
  testing::internal::CaptureStdout();
  EXPECT_EQ(apps::runDrift(options), 0);
  testing::internal::GetCapturedStdout();
  EXPECT_EQ(openDataset(options.out_dir)->size(), 4u);
}

TEST_F(DriftedSessionTest, DiffRefusesATrajectoryCountOtherThanTheSessions) {
  const std::string source = writeSmallSource(3);
  apps::DiffOptions options;
  options.sessions = {source, source};
  options.trajectories = {(fs::path(source) / "groundtruth.txt").string()};
  options.out_dir = (dir_ / "diff").string();
  options.quiet = true;
  testing::internal::CaptureStderr();
  EXPECT_EQ(apps::runDiff(options), 2);
  const std::string message = testing::internal::GetCapturedStderr();
  EXPECT_NE(message.find("--trajectory given 1 time(s) for 2 sessions"), std::string::npos)
      << message;
}

}  // namespace
}  // namespace strata::sim

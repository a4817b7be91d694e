// `strata sim --stereo` read back with the EuRoC reader, played with its RGB-D frames by
// strata-play --with-stereo, and the grey camera's exposure noise.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>

#include "cli/sim_command.h"
#include "strata/sim/sim_setup.h"
#include "strata/io/euroc_dataset.h"
#include "strata/io/tum_format.h"
#include "strata/lcm/channels.h"
#include "player/play_run.h"
#include "strata/odometry/pipeline/vio_replay.h"
#include "strata/sim/primitives.h"
#include "strata/sim/sensors/analytic_ray_scene.h"
#include "strata/sim/sensors/grey_camera.h"
#include "strata/sim/session/stereo_recording.h"

namespace strata::euroc {
namespace {

namespace fs = std::filesystem;

Eigen::Matrix3d expSO3(const Eigen::Vector3d& w) {
  const double angle = w.norm();
  if (angle < 1e-12) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, w / angle).toRotationMatrix();
}

class EurocSim : public testing::Test {
 protected:
  static void SetUpTestSuite() {
    out_ = fs::temp_directory_path() / ("strata_test_euroc_sim_" + std::to_string(::getpid()));
    fs::remove_all(out_);
    apps::SimOptions o;
    o.sessions = 1;
    o.max_frames = 44;  // RGB-D every ~0.5 s of the ~22 s path: two within the grey second
    o.out_dir = out_.string();
    o.quiet = true;
    o.stereo = true;
    o.stereo_duration_s = 1.0;
    o.stereo_width_px = 160;
    o.stereo_height_px = 120;
    ASSERT_EQ(apps::runSim(o), 0);
  }
  static void TearDownTestSuite() { fs::remove_all(out_); }
  static fs::path session() { return out_ / "session_0"; }
  static fs::path out_;
};
fs::path EurocSim::out_;

TEST_F(EurocSim, CalibrationCountsAndTimestampsReadBack) {
  const EurocDataset d = EurocDataset::open(session().string());
  ASSERT_TRUE(d.stereo());
  const CameraCalibration& cam0 = d.calibration().cameras[0];
  EXPECT_EQ(cam0.width_px, 160);
  EXPECT_EQ(cam0.height_px, 120);
  EXPECT_NEAR(cam0.fu_px, 0.61 * 160, 1e-12);
  EXPECT_NEAR(cam0.cu_px, 79.5, 1e-12);
  EXPECT_EQ(cam0.distortion, DistortionModel::kNone);
  EXPECT_TRUE(cam0.T_B_C.isApprox(sim::defaultT_C_B().inverse(), 1e-12));
  EXPECT_TRUE(d.calibration().T_C0_C1().isApprox(
      Eigen::Isometry3d(Eigen::Translation3d(0.11, 0.0, 0.0)), 1e-12));
  EXPECT_DOUBLE_EQ(d.calibration().imu.rate_hz, 200.0);
  EXPECT_DOUBLE_EQ(d.calibration().imu.accel_noise_density, 2.0e-3);

  ASSERT_EQ(d.frames().size(), 21u);  // t = 0 .. 1 s at 20 Hz
  ASSERT_EQ(d.imu().size(), 201u);    // at 200 Hz
  EXPECT_EQ(d.stats().imu_gaps, 0u);
  EXPECT_EQ(d.stats().unpaired_left + d.stats().unpaired_right + d.stats().missing_images, 0u);
  for (std::size_t k = 0; k < d.frames().size(); ++k) {
    EXPECT_EQ(d.frames()[k].timestamp_ns, static_cast<std::int64_t>(k) * 50'000'000);
    EXPECT_EQ(d.imu()[10 * k].timestamp_ns, d.frames()[k].timestamp_ns);  // a sample per frame
  }
  EXPECT_EQ(d.groundTruth().size(), d.imu().size());
  EXPECT_TRUE(d.groundTruth().front().has_velocity_and_biases);

  const StereoImages images = d.loadImages(10);
  double left_mean = 0.0;
  int differ = 0;
  for (std::size_t i = 0; i < images.left.pixels.size(); ++i) {
    left_mean += images.left.pixels[i];
    differ += images.left.pixels[i] != images.right.pixels[i];
  }
  left_mean /= static_cast<double>(images.left.pixels.size());
  EXPECT_GT(left_mean, 20.0);  // lit, textured room
  EXPECT_LT(left_mean, 240.0);
  EXPECT_GT(differ, static_cast<int>(images.left.pixels.size() / 4));  // another viewpoint
}

TEST_F(EurocSim, CalibrationAloneReadsAsTheReaderDoes) {
  const EurocDataset d = EurocDataset::open(session().string());
  for (const bool right : {true, false}) {
    const Calibration alone = readCalibration((session() / "mav0").string(), right);
    ASSERT_EQ(alone.cameras.size(), right ? 2u : 1u);
    for (std::size_t i = 0; i < alone.cameras.size(); ++i) {
      const CameraCalibration& a = alone.cameras[i];
      const CameraCalibration& b = d.calibration().cameras[i];
      EXPECT_EQ(a.name, b.name);
      EXPECT_EQ(a.width_px, b.width_px);
      EXPECT_EQ(a.fu_px, b.fu_px);
      EXPECT_TRUE(a.T_B_C.isApprox(b.T_B_C, 1e-15));
    }
    EXPECT_EQ(alone.imu.gyro_noise_density, d.calibration().imu.gyro_noise_density);
  }
}

TEST_F(EurocSim, TruthIsTheRgbdTrajectoryThroughTheMounting) {
  const EurocDataset d = EurocDataset::open(session().string());
  const auto world = sim::loadWorld("", 0, 1);
  const sim::SimSessionDataset sim_session(world, 0, sim::sessionConfig(30.0, 2, true, false));
  const Eigen::Isometry3d T_B_C0 = d.calibration().cameras[0].T_B_C;
  double worst_m = 0.0;
  for (const GroundTruthState& s : d.groundTruth()) {
    const Eigen::Isometry3d T_W_C = sim_session.trajectory().pose(s.timestamp_ns * 1e-9);
    worst_m = std::max(worst_m, ((s.T_W_B * T_B_C0).matrix() - T_W_C.matrix()).norm());
  }
  EXPECT_LT(worst_m, 1e-9);
  // groundtruth_body.txt holds the same body poses in TUM format.
  const std::vector<tum::TimedPose> body =
      tum::readTrajectory((session() / "groundtruth_body.txt").string());
  ASSERT_EQ(body.size(), d.groundTruth().size());
  for (std::size_t i = 0; i < body.size(); i += 10) {
    EXPECT_NEAR(body[i].timestamp_s, d.groundTruth()[i].timestamp_ns * 1e-9, 1e-9);
    EXPECT_LT((body[i].T_W_C.matrix() - d.groundTruth()[i].T_W_B.matrix()).norm(), 1e-7);
  }
  // The TUM RGB-D groundtruth.txt is cam0's trajectory: its first pose is at t = 0.
  const std::vector<tum::TimedPose> tum =
      tum::readTrajectory((session() / "groundtruth.txt").string());
  ASSERT_FALSE(tum.empty());
  EXPECT_NEAR(tum.front().timestamp_s, 0.0, 1e-9);
  EXPECT_LT(((d.groundTruth().front().T_W_B * T_B_C0).matrix() - tum.front().T_W_C.matrix()).norm(),
            1e-6);
}

// The recording in memory (what `strata demo --vio` replays) is what was written: same frame
// times, IMU samples, truth and images.
TEST_F(EurocSim, InMemoryRecordingIsWhatWasWritten) {
  const EurocDataset d = EurocDataset::open(session().string());
  const auto world = sim::loadWorld("", 0, 1);
  const sim::SimSessionDataset sim_session(world, 0, sim::sessionConfig(30.0, 2, true, false));
  sim::StereoRecordingConfig config = sim::stereoRecordingConfig(160, 120, true);
  config.duration_s = 1.0;
  const sim::StereoRecording recording(sim_session, config);
  ASSERT_EQ(recording.frameTimestamps().size(), d.frames().size());
  for (std::size_t k = 0; k < d.frames().size(); ++k)
    EXPECT_EQ(recording.frameTimestamps()[k], d.frames()[k].timestamp_ns);
  ASSERT_EQ(recording.imu().size(), d.imu().size());
  ASSERT_EQ(recording.groundTruth().size(), d.groundTruth().size());
  for (std::size_t i = 0; i < d.imu().size(); i += 7) {
    EXPECT_EQ(recording.imu()[i].timestamp_ns, d.imu()[i].timestamp_ns);
    EXPECT_LT((recording.imu()[i].accel_mps2 - d.imu()[i].accel_mps2).norm(), 1e-9);
    EXPECT_LT((recording.imu()[i].gyro_rad_s - d.imu()[i].gyro_rad_s).norm(), 1e-12);
    EXPECT_LT(
        (recording.groundTruth()[i].T_W_B.matrix() - d.groundTruth()[i].T_W_B.matrix()).norm(),
        1e-9);
  }
  EXPECT_TRUE(recording.calibration().T_C0_C1().isApprox(d.calibration().T_C0_C1(), 1e-12));
  const sim::GreyFrame frame = recording.renderFrame(10);
  const StereoImages images = d.loadImages(10);
  ASSERT_EQ(frame.eyes.size(), 2u);
  EXPECT_EQ(frame.eyes[0].pixels, images.left.pixels);
  EXPECT_EQ(frame.eyes[1].pixels, images.right.pixels);
}

// Strapdown integration of the recorded IMU (biases from the truth removed) from a truth state
// lands on the truth 0.5 s later: the IMU, the mounting and the body truth agree.
TEST_F(EurocSim, ImuIntegratesToTheTruth) {
  const EurocDataset d = EurocDataset::open(session().string());
  const std::vector<GroundTruthState>& gt = d.groundTruth();
  const std::vector<ImuSample>& imu = d.imu();
  const std::size_t first = 50, last = 150;  // t = 0.25 .. 0.75 s
  const Eigen::Vector3d g_W(0.0, 0.0, -9.81);
  Eigen::Matrix3d R = gt[first].T_W_B.linear();
  Eigen::Vector3d p = gt[first].T_W_B.translation();
  Eigen::Vector3d v = gt[first].velocity_W;
  double travelled_m = 0.0;
  for (std::size_t k = first; k < last; ++k) {
    const double dt = (imu[k + 1].timestamp_ns - imu[k].timestamp_ns) * 1e-9;
    // Midpoint of the two samples: second-order accurate at 200 Hz.
    const Eigen::Vector3d w = 0.5 * (imu[k].gyro_rad_s + imu[k + 1].gyro_rad_s) - gt[k].gyro_bias;
    const Eigen::Vector3d f0 = imu[k].accel_mps2 - gt[k].accel_bias;
    const Eigen::Vector3d f1 = imu[k + 1].accel_mps2 - gt[k].accel_bias;
    const Eigen::Matrix3d R1 = R * expSO3(w * dt);
    const Eigen::Vector3d a = 0.5 * (R * f0 + R1 * f1) + g_W;
    p += v * dt + 0.5 * a * dt * dt;
    v += a * dt;
    R = R1;
    travelled_m += (gt[k + 1].T_W_B.translation() - gt[k].T_W_B.translation()).norm();
  }
  EXPECT_GT(travelled_m, 0.1);  // it moved (about 0.19 m): the check is not trivial
  EXPECT_LT((p - gt[last].T_W_B.translation()).norm(), 0.005);  // measured 0.8 mm
  EXPECT_LT((v - gt[last].velocity_W).norm(), 0.015);           // measured 3 mm/s
  const double angle_rad = Eigen::AngleAxisd(R.transpose() * gt[last].T_W_B.linear()).angle();
  EXPECT_LT(angle_rad, 0.005);
}

/// What strata-play sent on memq://, in arrival order: (channel, utime) and frames' pose flags.
struct Sent {
  std::vector<std::pair<std::string, std::int64_t>> order;
  std::vector<bool> frame_has_pose;
  template <typename Message>
  Message decode(const lcm::ReceiveBuffer* buffer, const std::string& channel) {
    Message m;
    EXPECT_GT(m.decode(buffer->data, 0, static_cast<int>(buffer->data_size)), 0);
    order.emplace_back(channel, m.utime);
    return m;
  }
  void onRgbd(const lcm::ReceiveBuffer* b, const std::string& c) {
    frame_has_pose.push_back(decode<rgbd_frame_t>(b, c).has_pose);
  }
  void onStereo(const lcm::ReceiveBuffer* b, const std::string& c) { decode<stereo_image_t>(b, c); }
  void onImu(const lcm::ReceiveBuffer* b, const std::string& c) { decode<imu_t>(b, c); }
  void onPose(const lcm::ReceiveBuffer* b, const std::string& c) { decode<pose_t>(b, c); }
  std::vector<std::int64_t> utimes(const std::string& channel) const {
    std::vector<std::int64_t> out;
    for (const auto& [c, utime] : order)
      if (c == channel) out.push_back(utime);
    return out;
  }
};

TEST_F(EurocSim, PlayWithStereoSendsGreyAndRgbdOnOneClockWithoutPoses) {
  lcm::LCM lcm("memq://");
  Sent sent;
  lcm.subscribe(lcm_io::kRgbdChannel, &Sent::onRgbd, &sent);
  lcm.subscribe(lcm_io::kStereoChannel, &Sent::onStereo, &sent);
  lcm.subscribe(lcm_io::kImuChannel, &Sent::onImu, &sent);
  lcm.subscribe(lcm_io::kPoseChannel, &Sent::onPose, &sent);
  apps::PlayOptions o;
  o.dataset = session().string();
  o.with_stereo = true;
  o.poses = false;
  o.rate = 20.0;
  o.end_session = false;  // no mapper to answer
  o.quiet = true;
  ASSERT_EQ(apps::runPlay(o, lcm), 0);
  while (lcm.handleTimeout(0) > 0) {
  }

  const EurocDataset d = EurocDataset::open(session().string());
  const std::vector<tum::TimedPose> rgbd =
      tum::readTrajectory((session() / "groundtruth.txt").string());
  std::vector<double> inside;  // RGB-D frames within the grey recording (t = 0 .. 1 s)
  for (const tum::TimedPose& p : rgbd) {
    if (p.timestamp_s <= d.frames().back().timestamp_ns * 1e-9) inside.push_back(p.timestamp_s);
  }
  ASSERT_EQ(inside.size(), 2u);
  EXPECT_TRUE(sent.utimes(lcm_io::kPoseChannel).empty()) << "--no-poses sends no pose";
  for (bool has_pose : sent.frame_has_pose) EXPECT_FALSE(has_pose);
  for (std::size_t i = 1; i < sent.order.size(); ++i) {
    EXPECT_LE(sent.order[i - 1].second, sent.order[i].second) << "out of time order at " << i;
  }
  // One clock: every stamp is the first message's plus its recording time (both start at 0).
  ASSERT_EQ(sent.order.front().first, lcm_io::kImuChannel);
  const std::int64_t base = sent.order.front().second;
  const std::vector<std::int64_t> frames = sent.utimes(lcm_io::kRgbdChannel);
  ASSERT_EQ(frames.size(), inside.size()) << "frames outside the grey recording are not sent";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i], base + std::llround(inside[i] * 1e6));
  }
  // The grey stream goes on through the first grey frame at or after the last RGB-D frame.
  const std::vector<std::int64_t> grey = sent.utimes(lcm_io::kStereoChannel);
  std::size_t expected = 0;
  while (d.frames()[expected].timestamp_ns * 1e-9 < inside.back() - 1e-7) ++expected;
  ASSERT_EQ(grey.size(), expected + 1);
  for (std::size_t k = 0; k < grey.size(); ++k) {
    EXPECT_EQ(grey[k], base + d.frames()[k].timestamp_ns / 1000);
  }
  const std::vector<std::int64_t> imu = sent.utimes(lcm_io::kImuChannel);
  EXPECT_EQ(imu.back(), grey.back()) << "the IMU sample at the last grey frame's stamp";
  EXPECT_EQ(imu.size(), static_cast<std::size_t>(grey.size() - 1) * 10 + 1);  // 200 Hz, 20 Hz
}

// The poses `strata demo --vio` fuses: the left camera between two tracked frames, nothing before
// the first, after the last or across a gap.
TEST(VioReplay, CameraPoseBetweenTrackedFramesNoneAcrossGaps) {
  std::vector<odometry::PipelineFrame> tracked(3);
  for (std::size_t k = 0; k < tracked.size(); ++k) {
    tracked[k].status = odometry::VioStatus::kTracking;
    tracked[k].T_W_C.translation() = Eigen::Vector3d(0.1 * k, 0.0, 1.0);
  }
  tracked[0].timestamp_ns = 1'000'000'000;
  tracked[1].timestamp_ns = 1'050'000'000;
  tracked[2].timestamp_ns = 1'150'000'000;  // a frame missing before it
  tracked[1].T_W_C.linear() = expSO3(Eigen::Vector3d(0.0, 0.0, 0.2));
  const std::int64_t gap = 75'000'000;
  const auto mid = odometry::interpolateCameraPose(tracked, 1'025'000'000, gap);
  ASSERT_TRUE(mid.has_value());
  EXPECT_LT((mid->translation() - Eigen::Vector3d(0.05, 0.0, 1.0)).norm(), 1e-12);
  EXPECT_LT((mid->linear() - expSO3(Eigen::Vector3d(0.0, 0.0, 0.1))).norm(), 1e-12);
  const auto at = odometry::interpolateCameraPose(tracked, 1'050'000'000, gap);
  ASSERT_TRUE(at.has_value());
  EXPECT_TRUE(at->isApprox(tracked[1].T_W_C));
  EXPECT_FALSE(odometry::interpolateCameraPose(tracked, 999'999'999, gap).has_value());
  EXPECT_FALSE(odometry::interpolateCameraPose(tracked, 1'100'000'000, gap).has_value());
  EXPECT_FALSE(odometry::interpolateCameraPose(tracked, 1'150'000'001, gap).has_value());
  EXPECT_TRUE(odometry::interpolateCameraPose(tracked, 1'100'000'000, 2 * gap).has_value());
}

TEST(EurocGreyExposure, GainAndOffsetPerFrameSeeded) {
  sim::AnalyticRayScene scene(1);
  scene.add(sim::Plane{Eigen::Vector3d(0, 0, 2.0), Eigen::Vector3d(0, 0, -1), {180, 180, 180}});
  sim::GreyCameraConfig config;
  config.intrinsics.width_px = 40;
  config.intrinsics.height_px = 30;
  config.intrinsics.fx_px = config.intrinsics.fy_px = 40.0f;
  config.intrinsics.cx_px = 19.5f;
  config.intrinsics.cy_px = 14.5f;
  config.pixel_noise_sigma = 0.0;
  config.baseline_m = 0.05;
  sim::Lighting light;
  light.direction_W = Eigen::Vector3d(0, 0, -1);
  const sim::GreyCamera flat(config);
  config.exposure_gain_sigma = 0.1;
  config.exposure_offset_sigma = 5.0;
  const sim::GreyCamera noisy(config);
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  const sim::GreyFrame reference = flat.render(scene, pose, light, 7);
  EXPECT_EQ(reference.exposure_gain, 1.0);
  int gains_differ = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const sim::GreyFrame f = noisy.render(scene, pose, light, seed);
    EXPECT_EQ(f.eyes[0].pixels, noisy.render(scene, pose, light, seed).eyes[0].pixels);  // seeded
    gains_differ += std::abs(f.exposure_gain - 1.0) > 1e-3;
    for (std::size_t eye = 0; eye < 2; ++eye) {
      for (std::size_t i = 0; i < f.eyes[eye].pixels.size(); i += 37) {
        const double expected = std::clamp(
            f.exposure_gain * reference.eyes[eye].pixels[i] + f.exposure_offset, 0.0, 255.0);
        EXPECT_NEAR(f.eyes[eye].pixels[i], expected, 0.5 * f.exposure_gain + 0.51);
      }
    }
  }
  EXPECT_GE(gains_differ, 4);
  config.exposure_gain_sigma = 0.6;
  EXPECT_THROW(sim::GreyCamera{config}, InputError);
}

}  // namespace
}  // namespace strata::euroc

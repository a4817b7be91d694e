// strata-localizer's node in-process over memq://: a prior map made of a simulated session of the
// shipped room (a map database, every frame a keyframe), live frames of the same session at
// other places along its path, and odometry in a frame of its own (a known offset) that drifts.
// The node must publish map-frame poses close to the truth once initialised, a status per frame,
// refuse (and count) odometry whose time goes backwards or repeats, and refuse map databases it
// cannot use before it subscribes to anything.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <mutex>
#include <thread>

#include "localizer_node/localizer_core.h"
#include "localizer_node/localizer_node.h"
#include "store_test_helpers.h"
#include "strata/core/error.h"
#include "strata/io/tum_writer.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_pose.h"
#include "strata/sim/sim_setup.h"
#include "strata/store/session_import.h"
#include "strata/store/session_store.h"
#include "test_utils.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

constexpr int kMapFrames = 24;
constexpr int kLiveFrames = 48;
constexpr int kInitFrames = 8;  // streamed before the test waits for their localisations
constexpr std::int64_t kStartUtime = 1'700'000'000'000'000;
constexpr std::int64_t kFramePeriodUs = 50'000;  // a 20 Hz camera

sim::SimSessionConfig roomConfig(int frames) {
  sim::SimSessionConfig config = sim::sessionConfig(30.0, frames, true, false);
  config.camera.color_texture = sim::WorldTextureConfig{};  // texture for ORB
  return config;
}

/// The odometry frame: T_O_W, a yaw and a shift, drifting along the path (T_O_W grows a shift
/// of 1 mm and 0.02 degrees of yaw per frame: 2-3 mm a frame where the camera is, so that a
/// localisation every 10 frames, on a busy machine, still keeps the poses within 5 cm).
Eigen::Isometry3d odometryFromWorld(int frame) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(0.5 + 0.02 * M_PI / 180.0 * frame, Eigen::Vector3d::UnitZ())
                   .toRotationMatrix();
  T.translation() = Eigen::Vector3d(2.0 + 0.001 * frame, -1.0, 0.3);
  return T;
}

/// What the node publishes, kept for the assertions (handlers run on its receive thread).
struct Outputs {
  std::mutex mutex;
  std::map<std::int64_t, Eigen::Isometry3d> poses;  // by utime
  std::vector<localization_status_t> statuses;
  void onPose(const lcm::ReceiveBuffer* b, const std::string&) {
    pose_t m;
    ASSERT_GT(m.decode(b->data, 0, static_cast<int>(b->data_size)), 0);
    EXPECT_EQ(m.parent_frame, lcm_io::kWorldFrame);
    std::lock_guard<std::mutex> lock(mutex);
    poses[m.utime] = lcm_io::decodePose(m);
  }
  void onStatus(const lcm::ReceiveBuffer* b, const std::string&) {
    localization_status_t m;
    ASSERT_GT(m.decode(b->data, 0, static_cast<int>(b->data_size)), 0);
    std::lock_guard<std::mutex> lock(mutex);
    statuses.push_back(m);
  }
};

class LocalizerNodeTest : public testing::Test {
 protected:
  /// The prior map's database, and the live session rendered once per test program.
  static void SetUpTestSuite() {
    dir_ = new fs::path(freshStoreDir("localizer_node"));
    const auto world = sim::loadWorld("", 0, 1);
    const sim::SimSessionDataset recorded(world, 0, roomConfig(kMapFrames));
    TumWriter writer((*dir_ / "room_0").string(), recorded.intrinsics());
    for (std::size_t i = 0; i < recorded.size(); ++i) {
      RgbdFrame frame = recorded.load(i);
      frame.T_W_C = recorded.truePoses()[i];
      writer.add(frame);
    }
    writer.finish();
    store::Store db((*dir_ / "map.sqlite").string());
    store::ImportOptions import;
    import.keyframe_every = 1;
    store::importTumSession(db, (*dir_ / "room_0").string(), import);
    live_ = new sim::SimSessionDataset(world, 0, roomConfig(kLiveFrames));
  }
  static void TearDownTestSuite() {
    delete live_;
    fs::remove_all(*dir_);
    delete dir_;
  }
  static apps::LocalizerOptions options() {
    apps::LocalizerOptions o;
    o.url = "memq://";
    o.db_path = (*dir_ / "map.sqlite").string();
    o.every = 2;
    o.max_idle_s = 1.0;
    o.quiet = true;
    return o;
  }
  static fs::path* dir_;
  static sim::SimSessionDataset* live_;
};
fs::path* LocalizerNodeTest::dir_ = nullptr;
sim::SimSessionDataset* LocalizerNodeTest::live_ = nullptr;

TEST_F(LocalizerNodeTest, PublishesMapFramePosesCloseToTheTruthAndRefusesTimeGoingBack) {
  apps::LocalizerOptions o = options();
  o.max_idle_s = 0.0;  // stopped by the test once every status is out
  const localize::PriorMap map = apps::loadPriorMap(o);
  ASSERT_EQ(map.keyframes().size(), static_cast<std::size_t>(kMapFrames));
  apps::LocalizerCore core(map, o);
  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  apps::LocalizerNode node(lcm, lcm, core, o);
  Outputs out;
  lcm.subscribe(o.channels.pose, &Outputs::onPose, &out);
  lcm.subscribe(o.channels.status, &Outputs::onStatus, &out);

  // Rendered before the node runs, so the stream keeps the camera's pace.
  std::vector<rgbd_frame_t> frames;
  std::map<std::int64_t, Eigen::Isometry3d> truth;
  lcm_io::FrameEncoding encoding;
  encoding.with_pose = false;
  for (int i = 0; i < kLiveFrames; ++i) {
    const std::int64_t utime = kStartUtime + i * kFramePeriodUs;
    frames.push_back(
        lcm_io::encodeFrame(live_->load(static_cast<std::size_t>(i)), utime, "rgbd", i, encoding));
    truth[utime] = live_->truePoses()[static_cast<std::size_t>(i)];
  }
  std::atomic<bool> stop{false};
  apps::LocalizerSnapshot result;
  std::thread runner([&] { result = node.run(stop); });
  const camera_info_t info = lcm_io::encodeCameraInfo(live_->intrinsics(), "rgbd", kStartUtime);
  ASSERT_EQ(lcm.publish(o.channels.camera_info, &info), 0);
  // Until every status of `count` frames is out (the node has handled them), at most 180 s.
  const auto waitForStatuses = [&](std::size_t count) {
    for (int k = 0; k < 1800; ++k) {
      {
        std::lock_guard<std::mutex> lock(out.mutex);
        if (out.statuses.size() >= count) return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
    }
  };
  for (int i = 0; i < kLiveFrames; ++i) {
    const std::int64_t utime = kStartUtime + i * kFramePeriodUs;
    const pose_t odometry =
        lcm_io::encodePose(odometryFromWorld(i) * truth.at(utime), utime, lcm_io::kWorldFrame);
    ASSERT_EQ(lcm.publish(o.channels.odometry, &odometry), 0);
    ASSERT_EQ(lcm.publish(o.channels.rgbd, &frames[static_cast<std::size_t>(i)]), 0);
    std::this_thread::sleep_for(std::chrono::microseconds(kFramePeriodUs));
    // The first frames' localisations have to be done before the rest is judged: under the
    // sanitizers a localisation takes 2 s, longer than the whole stream at 20 Hz.
    if (i == kInitFrames - 1) waitForStatuses(kInitFrames);
  }
  // A gap (the camera stood still for a second): taken, counted. Then time going backwards, and
  // repeating: both refused and counted, neither gets a pose out.
  const std::int64_t before_gap = kStartUtime + (kLiveFrames - 1) * kFramePeriodUs;
  const std::int64_t last = before_gap + 1'000'000;
  truth[last] = truth.at(before_gap);
  const pose_t after_gap = lcm_io::encodePose(odometryFromWorld(kLiveFrames - 1) * truth.at(last),
                                              last, lcm_io::kWorldFrame);
  ASSERT_EQ(lcm.publish(o.channels.odometry, &after_gap), 0);
  for (const std::int64_t utime : {last - 3 * kFramePeriodUs, last}) {
    const pose_t back = lcm_io::encodePose(Eigen::Isometry3d::Identity(), utime);
    ASSERT_EQ(lcm.publish(o.channels.odometry, &back), 0);
  }
  waitForStatuses(kLiveFrames);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));  // the last odometry poses
  stop = true;
  runner.join();

  const apps::LocalizerCounters& c = result.counters;
  std::printf("%s", apps::localizerSummary(result).c_str());
  EXPECT_EQ(result.stopped_by, "signal");
  EXPECT_EQ(c.frames_received, kLiveFrames);
  EXPECT_EQ(c.frames_ready, kLiveFrames);
  EXPECT_EQ(c.odometry_received, kLiveFrames + 3);
  EXPECT_EQ(c.odometry_refused, 2);
  EXPECT_EQ(c.odometry_gaps, 1);
  EXPECT_EQ(c.frames_skipped_every, kLiveFrames / 2);
  EXPECT_EQ(c.frames_attempted + c.frames_skipped_busy, kLiveFrames / 2);
  EXPECT_TRUE(result.initialised);
  EXPECT_GE(c.frames_localized, 3);
  EXPECT_GE(result.corrections_accepted, 2);

  std::lock_guard<std::mutex> lock(out.mutex);
  // A status per frame: those skipped by --every or while busy, and those tried.
  EXPECT_EQ(static_cast<std::int64_t>(out.statuses.size()), kLiveFrames);
  const auto corrected = std::count_if(out.statuses.begin(), out.statuses.end(), [](auto& s) {
    return s.status == localization_status_t::CORRECTED && s.attempted && s.localized;
  });
  EXPECT_GE(corrected, 2);
  // Map-frame poses: one per odometry pose from the initialisation on, none for refused ones.
  EXPECT_EQ(static_cast<std::int64_t>(out.poses.size()), c.poses_published);
  EXPECT_EQ(c.poses_published + c.poses_uninitialised, kLiveFrames + 1);
  EXPECT_EQ(out.poses.count(last), 1u);
  ASSERT_GE(out.poses.size(), static_cast<std::size_t>(kLiveFrames / 3));
  std::vector<double> errors_m;
  double worst_deg = 0.0;
  for (const auto& [utime, T_W_C] : out.poses) {
    ASSERT_TRUE(truth.count(utime)) << utime;
    const Eigen::Isometry3d error = truth.at(utime).inverse() * T_W_C;
    errors_m.push_back(error.translation().norm());
    worst_deg = std::max(worst_deg, Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI);
  }
  std::sort(errors_m.begin(), errors_m.end());
  const double median_m = errors_m[errors_m.size() / 2];
  std::printf(
      "localizer node: %zu map-frame poses, error %.1f mm median, %.1f mm worst, %.2f deg "
      "worst\n",
      out.poses.size(), 1e3 * median_m, 1e3 * errors_m.back(), worst_deg);
  // Without the corrections the odometry is metres off (the offset) and drifts ~10 cm by the end.
  EXPECT_LT(median_m, 0.025);
  EXPECT_LT(errors_m.back(), 0.05);
  EXPECT_LT(worst_deg, 2.0);
}

TEST_F(LocalizerNodeTest, MissingCorruptAndNewerDatabasesAreRefusedNamingTheFile) {
  apps::LocalizerOptions o = options();
  const fs::path dir = freshStoreDir("localizer_bad_db");
  auto refusal = [&](const fs::path& db) {
    o.db_path = db.string();
    try {
      apps::loadPriorMap(o);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(accepted)");
  };
  const std::string missing = refusal(dir / "none.sqlite");
  EXPECT_NE(missing.find("none.sqlite"), std::string::npos) << missing;
  EXPECT_FALSE(fs::exists(dir / "none.sqlite"));  // read-only: nothing created
  writeRandomFile(dir / "garbage.sqlite", 4096, 7);
  const std::string garbage = refusal(dir / "garbage.sqlite");
  EXPECT_NE(garbage.find("garbage.sqlite"), std::string::npos) << garbage;
  fs::copy_file(*dir_ / "map.sqlite", dir / "newer.sqlite");
  execSql(dir / "newer.sqlite", "PRAGMA user_version = 99");
  const std::string newer = refusal(dir / "newer.sqlite");
  EXPECT_NE(newer.find("version 99"), std::string::npos) << newer;
  { store::Store empty((dir / "empty.sqlite").string()); }
  const std::string empty = refusal(dir / "empty.sqlite");
  EXPECT_NE(empty.find("no session"), std::string::npos) << empty;
  fs::remove_all(dir);
}

TEST(LocalizerCarry, ALateLocalisationIsCarriedThroughTheOdometry) {
  localize::Localization l;
  l.localized = true;
  l.T_W_C = samplePose(1);
  l.covariance = Eigen::Matrix<double, 6, 6>::Identity() * 1e-4;
  const Eigen::Isometry3d T_O_C_frame = samplePose(2);
  const Eigen::Isometry3d T_O_C_now = samplePose(3);
  const localize::Localization carried = apps::carryLocalization(l, T_O_C_frame, T_O_C_now);
  // Both imply the same correction T_W_O.
  const Eigen::Isometry3d a = l.T_W_C * T_O_C_frame.inverse();
  const Eigen::Isometry3d b = carried.T_W_C * T_O_C_now.inverse();
  EXPECT_TRUE(a.isApprox(b, 1e-9));
  // An isotropic rotation uncertainty stays isotropic; the lever arm adds translation variance.
  const Eigen::Matrix3d rotation = carried.covariance.bottomRightCorner<3, 3>();
  const Eigen::Matrix3d translation = carried.covariance.topLeftCorner<3, 3>();
  EXPECT_NEAR(rotation.trace(), 3e-4, 1e-12);
  EXPECT_GE(translation.trace(), 3e-4 - 1e-12);
}

}  // namespace
}  // namespace strata::test

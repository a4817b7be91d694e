// strata-vio's node in-process over memq://: the EuRoC excerpt's grey stereo + IMU in, poses out,
// with corrupt, wrong-size, non-finite and out-of-order messages mixed into the streams. Each bad
// message is counted by its kind and skipped, none gets a pose, and the poses of the good frames
// are those of the same streams without the bad messages (to 1 um).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <set>
#include <vector>

#include "strata/io/euroc_dataset.h"
#include "strata/lcm/channels.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/convert_stereo.h"
#include "strata/pose_t.hpp"
#include "test_utils.h"
#include "vio_node/vio_core.h"
#include "vio_node/vio_node.h"

namespace strata::test {
namespace {

using lcm_io::ImuMsg;
using lcm_io::StereoFrameMsg;

struct PoseCollector {
  std::vector<apps::VioPose> poses;
  std::vector<std::string> child_frames;
  void onPose(const lcm::ReceiveBuffer* buffer, const std::string&) {
    pose_t m;
    ASSERT_GT(m.decode(buffer->data, 0, static_cast<int>(buffer->data_size)), 0);
    EXPECT_EQ(m.parent_frame, lcm_io::kWorldFrame);
    child_frames.push_back(m.child_frame);
    poses.push_back({m.utime, lcm_io::decodePose(m)});
  }
};

/// The excerpt's events as the messages strata-play sends (recording stamps, ns / 1000).
class Stream {
 public:
  explicit Stream(const euroc::EurocDataset& d) : d_(d) {}
  ImuMsg imu(std::size_t i) const {
    const euroc::ImuSample& s = d_.imu()[i];
    return {s.timestamp_ns / 1000, "imu0", s.gyro_rad_s, s.accel_mps2};
  }
  StereoFrameMsg frame(std::size_t i, std::int64_t utime) const {
    const euroc::StereoImages images = d_.loadImages(i);
    return lcm_io::decodeStereo(lcm_io::encodeStereo(images.left, images.right, utime,
                                                     static_cast<std::int64_t>(i), "cam0", "cam1"));
  }
  std::int64_t frameUtime(std::size_t i) const { return d_.frames()[i].timestamp_ns / 1000; }

 private:
  const euroc::EurocDataset& d_;
};

template <typename Message>
void publish(lcm::LCM& lcm, const char* channel, const Message& m) {
  ASSERT_EQ(lcm.publish(channel, &m), 0);
}

void publishBytes(lcm::LCM& lcm, const char* channel, const std::vector<std::uint8_t>& bytes) {
  ASSERT_EQ(lcm.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size())), 0);
}

template <typename Message>
std::vector<std::uint8_t> encoded(const Message& m) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

/// The bad messages, sent after frame `k` of the stream. Returns the stamps of the bad frames
/// that carry a stamp of their own (none may get a pose).
std::vector<std::int64_t> publishBadMessages(lcm::LCM& lcm, const Stream& s, std::size_t k) {
  const std::int64_t t = s.frameUtime(k);
  // Stereo: garbage; a valid message cut short; 100x80 images; a mono message to a stereo rig;
  // an older frame again (time going back).
  publishBytes(lcm, lcm_io::kStereoChannel, std::vector<std::uint8_t>(300, 0xAB));
  std::vector<std::uint8_t> cut = encoded(lcm_io::encodeStereo(
      GreyImage(752, 480, 9), GreyImage(752, 480, 9), t + 500, 900, "cam0", "cam1"));
  cut.resize(cut.size() / 2);
  publishBytes(lcm, lcm_io::kStereoChannel, cut);
  publish(lcm, lcm_io::kStereoChannel,
          lcm_io::encodeStereo(GreyImage(100, 80, 50), GreyImage(100, 80, 50), t + 1000, 901,
                               "cam0", "cam1"));
  publish(lcm, lcm_io::kStereoChannel,
          lcm_io::encodeStereo(GreyImage(752, 480, 50), {}, t + 2000, 902, "cam0", ""));
  const StereoFrameMsg old = s.frame(k - 10, s.frameUtime(k - 10));
  publish(lcm, lcm_io::kStereoChannel,
          lcm_io::encodeStereo(old.left, old.right, old.utime, 903, "cam0", "cam1"));
  // IMU: garbage; a negative stamp; NaN; an older sample again (time going back).
  publishBytes(lcm, lcm_io::kImuChannel, std::vector<std::uint8_t>(40, 0x01));
  ImuMsg negative = s.imu(0);
  negative.utime = -5;
  publish(lcm, lcm_io::kImuChannel, lcm_io::encodeImu(negative));
  ImuMsg nan = s.imu(0);
  nan.utime = t + 3000;
  nan.gyro_rad_s.y() = std::numeric_limits<double>::quiet_NaN();
  publish(lcm, lcm_io::kImuChannel, lcm_io::encodeImu(nan));
  publish(lcm, lcm_io::kImuChannel, lcm_io::encodeImu(s.imu(0)));
  return {t + 500, t + 1000, t + 2000, t + 3000};
}

/// The poses of the clean streams, through the same VioCore the node runs.
std::vector<apps::VioPose> cleanPoses(const euroc::EurocDataset& d, const Stream& s,
                                      const odometry::VioPipelineConfig& config) {
  apps::VioCore core(euroc::readCalibration(d.folder()), config);
  std::vector<apps::VioPose> poses;
  for (const euroc::Event& e : d.events()) {
    const auto out = e.kind == euroc::Event::Kind::kImu
                         ? core.onImu(s.imu(e.index))
                         : core.onFrame(s.frame(e.index, s.frameUtime(e.index)));
    poses.insert(poses.end(), out.begin(), out.end());
  }
  return poses;
}

TEST(VioNode, CountsAndSkipsBadMessagesAndPublishesPosesOfGoodFramesOnly) {
  STRATA_REQUIRE_DATA("euroc_v101_micro", folder);
  const euroc::EurocDataset d = euroc::EurocDataset::open(folder);
  const Stream s(d);
  constexpr std::size_t kBadAfterFrame = 40;

  lcm::LCM lcm("memq://");
  ASSERT_TRUE(lcm.good());
  apps::VioOptions options;
  options.url = "memq://";
  options.calib_dir = folder;
  options.queue_frames = 1000;  // everything is published before the node runs: no backlog
  options.max_idle_s = 0.5;
  options.quiet = true;
  // NOTE: the back end's solver stops at a wall-time cap (30 ms), which makes two runs on a busy
  // machine differ (~0.1 mm, at times more); without the cap two runs agree to ~1e-11 m (an
  // order of summation that varies between runs), so the node's poses must equal the clean run's.
  options.pipeline.backend.max_solver_time_s = 60.0;
  apps::VioNode node(lcm, lcm, euroc::readCalibration(folder), options);
  PoseCollector collector;
  lcm.subscribe(lcm_io::kPoseChannel, &PoseCollector::onPose, &collector);

  std::vector<std::int64_t> bad_stamps;
  for (const euroc::Event& e : d.events()) {
    if (e.kind == euroc::Event::Kind::kImu) {
      publish(lcm, lcm_io::kImuChannel, lcm_io::encodeImu(s.imu(e.index)));
      continue;
    }
    const StereoFrameMsg f = s.frame(e.index, s.frameUtime(e.index));
    publish(lcm, lcm_io::kStereoChannel,
            lcm_io::encodeStereo(f.left, f.right, f.utime, f.sequence, "cam0", "cam1"));
    if (e.index == kBadAfterFrame) bad_stamps = publishBadMessages(lcm, s, kBadAfterFrame);
  }
  const std::atomic<bool> stop{false};
  const apps::VioSnapshot snapshot = node.run(stop);
  while (lcm.handleTimeout(0) > 0) {
  }

  EXPECT_EQ(snapshot.stopped_by, "idle");
  const apps::VioCounters& c = snapshot.counters;
  const std::int64_t frames = static_cast<std::int64_t>(d.frames().size());
  EXPECT_EQ(c.frames_received, frames + 5);
  EXPECT_EQ(c.frames_corrupt, 2) << "garbage and a truncated payload";
  EXPECT_EQ(c.frames_bad_image, 2) << "100x80 images and a missing right image";
  EXPECT_EQ(snapshot.pipeline.frames_out_of_order_skipped, 1u);
  EXPECT_EQ(c.frames_dropped_backlog, 0);
  EXPECT_EQ(c.imu_received, static_cast<std::int64_t>(d.imu().size()) + 4);
  EXPECT_EQ(c.imu_corrupt, 2) << "garbage and a negative stamp";
  EXPECT_EQ(c.imu_nonfinite, 1);
  EXPECT_EQ(snapshot.pipeline.imu_out_of_order_skipped, 1u);
  EXPECT_EQ(snapshot.pipeline.imu_samples, d.imu().size());
  EXPECT_EQ(snapshot.pipeline.frames_processed, d.frames().size());

  // Poses: one per tracked frame, at good frames' stamps only, those of the clean run.
  ASSERT_GT(snapshot.pipeline.frames_tracking, d.frames().size() / 2);
  EXPECT_EQ(c.poses_published, static_cast<std::int64_t>(snapshot.pipeline.frames_tracking));
  ASSERT_EQ(collector.poses.size(), snapshot.pipeline.frames_tracking);
  std::set<std::int64_t> good;
  for (std::size_t i = 0; i < d.frames().size(); ++i) good.insert(s.frameUtime(i));
  for (std::size_t i = 0; i < collector.poses.size(); ++i) {
    EXPECT_EQ(good.count(collector.poses[i].utime), 1u) << collector.poses[i].utime;
    if (i > 0) {
      EXPECT_GT(collector.poses[i].utime, collector.poses[i - 1].utime);
    }
    EXPECT_EQ(collector.child_frames[i], "cam0");
  }
  for (std::int64_t t : bad_stamps) EXPECT_EQ(good.count(t), 0u);
  const std::vector<apps::VioPose> clean = cleanPoses(d, s, options.pipeline);
  ASSERT_EQ(clean.size(), collector.poses.size());
  for (std::size_t i = 0; i < clean.size(); ++i) {
    EXPECT_EQ(clean[i].utime, collector.poses[i].utime);
    const Eigen::Isometry3d delta = clean[i].T_W_C.inverse() * collector.poses[i].T_W_C;
    EXPECT_LT(delta.translation().norm(), 1e-6) << "pose " << i;
    EXPECT_LT(Eigen::AngleAxisd(delta.rotation()).angle(), 1e-6) << "pose " << i;
  }
}

TEST(VioNode, SummaryAndStatusLineNameEveryKind) {
  apps::VioSnapshot s;
  s.counters.frames_received = 12;
  s.counters.frames_corrupt = 1;
  s.counters.imu_nonfinite = 2;
  s.pipeline.frames_tracking = 7;
  s.pipeline.frames_initializing = 3;
  s.pipeline.failures = 1;
  s.pipeline.frames_out_of_order_skipped = 1;
  s.pipeline.failure_log.push_back({2'000'000'000, "too few \"features\""});
  s.last_failure = "too few \"features\"";
  s.stopped_by = "signal";
  const std::string line = apps::vioStatusLine(s, 19.5);
  EXPECT_NE(line.find("12 frames in, 7 tracked, 3 initialising, 1 failures"), std::string::npos)
      << line;
  EXPECT_NE(line.find("last: too few"), std::string::npos) << line;
  EXPECT_NE(line.find("2 frames skipped; IMU 0 in, 2 skipped"), std::string::npos) << line;
  EXPECT_NE(line.find("19.5 frames/s"), std::string::npos) << line;
  const std::string json = apps::vioSummaryJson(s, "/data/session");
  for (const char* part :
       {"\"frames_received\": 12", "\"frames_tracked\": 7", "\"failures\": 1",
        "\"stopped_by\": \"signal\"", "\"corrupt\": 1", "\"out_of_order\": 1", "\"nonfinite\": 2",
        "\"reason\": \"too few \\\"features\\\"\"", "\"utime\": 2000000"}) {
    EXPECT_NE(json.find(part), std::string::npos) << part << " in " << json;
  }
}

TEST(VioNode, ARunThatTrackedNothingExitsThreeAndSaysWhy) {
  apps::VioSnapshot s;
  std::string message;
  EXPECT_EQ(apps::vioVerdict(s, &message), 0) << "nothing came: nothing to judge";
  EXPECT_EQ(message, "");

  s.pipeline.frames_processed = 40;
  s.pipeline.frames_initializing = 40;
  s.initialising_reason = "waiting for parallax";
  s.pipeline.imu_out_of_range_skipped = 900;
  EXPECT_EQ(apps::vioVerdict(s, &message), 3);
  EXPECT_NE(message.find("40 frames processed and none tracked (never initialised: waiting for "
                         "parallax)"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("900 IMU samples beyond any IMU's range"), std::string::npos) << message;
  EXPECT_NE(apps::vioSummaryJson(s, "/data").find("\"out_of_range\": 900"), std::string::npos);

  s.pipeline.frames_tracking = 1;
  EXPECT_EQ(apps::vioVerdict(s, &message), 0) << "a tracked frame is a trajectory";
  EXPECT_EQ(message.find("none tracked"), std::string::npos) << message;
  EXPECT_NE(message.find("900 IMU samples"), std::string::npos) << "the warning stays";
}

/// Out-of-range IMU samples are skipped and counted like NaN ones: no pose comes of them.
TEST(VioNode, ImuSamplesNoImuCouldGiveAreSkippedAndCounted) {
  STRATA_REQUIRE_DATA("euroc_v101_micro", folder);
  const euroc::EurocDataset d = euroc::EurocDataset::open(folder);
  apps::VioCore core(euroc::readCalibration(d.folder()), odometry::VioPipelineConfig{});
  const Stream s(d);
  ImuMsg spin = s.imu(0);
  spin.gyro_rad_s = {0.0, 0.0, 1.5 * odometry::kMaxImuAngularRate_rad_s};
  EXPECT_TRUE(core.onImu(spin).empty());
  ImuMsg shock = s.imu(1);
  shock.accel_mps2 = {0.0, 0.0, -1.5 * odometry::kMaxImuAcceleration_mps2};
  EXPECT_TRUE(core.onImu(shock).empty());
  EXPECT_EQ(core.stats().imu_out_of_range_skipped, 2u);
  EXPECT_EQ(core.stats().imu_samples, 0u);
  EXPECT_TRUE(core.onImu(s.imu(2)).empty());
  EXPECT_EQ(core.stats().imu_samples, 1u) << "an ordinary sample is taken";
}

}  // namespace
}  // namespace strata::test

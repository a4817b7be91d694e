// Visual-inertial odometry from raw streams (odometry/pipeline/vio_pipeline.h) and `strata
// odometry`: a simulated room session recorded by `strata sim --stereo --rest` (stereo and mono
// against the truth, a blackout that forces a re-initialisation in one continuous world frame),
// the bad inputs a live stream brings, and the real EuRoC V1_01 excerpt (standstill).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>

#include "cli/odometry_command.h"
#include "cli/odometry_summary.h"
#include "cli/sim_command.h"
#include "strata/core/error.h"
#include "strata/io/euroc_dataset.h"
#include "strata/io/tum_format.h"
#include "strata/odometry/pipeline/vio_pipeline.h"
#include "strata/odometry/pipeline/vio_replay.h"
#include "test_utils.h"

namespace strata::odometry {
namespace {

namespace fs = std::filesystem;

struct Replay {
  std::vector<PipelineFrame> tracked;
  PipelineStats stats;
};

// The whole session through the pipeline (odometry::replayVio, as `strata odometry` does);
// `edit` may change a frame's images before they are pushed.
Replay replay(const euroc::EurocDataset& d, VioPipelineConfig config,
              const std::function<void(std::int64_t, euroc::StereoImages&)>& edit = {}) {
  VioPipeline pipeline(d.calibration(), std::move(config));
  ReplayInput input;
  input.imu = &d.imu();
  for (const euroc::StereoFrame& f : d.frames())
    input.frame_timestamps_ns.push_back(f.timestamp_ns);
  input.load = [&](std::size_t k) {
    euroc::StereoImages images = d.loadImages(k);
    if (edit) edit(d.frames()[k].timestamp_ns, images);
    return images;
  };
  ReplayResult result = replayVio(pipeline, input);
  return {std::move(result.tracked), std::move(result.stats)};
}

class VioPipelineSim : public testing::Test {
 protected:
  // A 10 s hand-held path through the room after 1.5 s at rest, 376x240 grey stereo at 20 Hz,
  // IMU at 200 Hz, the simulator's image and IMU noise on.
  static void SetUpTestSuite() {
    out_ = fs::temp_directory_path() / ("strata_test_vio_" + std::to_string(::getpid()));
    fs::remove_all(out_);
    apps::SimOptions o;
    o.sessions = 1;
    o.max_frames = 2;
    o.out_dir = out_.string();
    o.quiet = true;
    o.stereo = true;
    o.rest_s = 1.5;
    o.stereo_duration_s = 11.5;
    o.stereo_width_px = 376;
    o.stereo_height_px = 240;
    ASSERT_EQ(apps::runSim(o), 0);
  }
  static void TearDownTestSuite() { fs::remove_all(out_); }
  static std::string session() { return (out_ / "session_0").string(); }
  static fs::path out_;
};
fs::path VioPipelineSim::out_;

TEST_F(VioPipelineSim, StereoFollowsTheTruthWithoutFailure) {
  const auto d = euroc::EurocDataset::open(session());
  const Replay r = replay(d, VioPipelineConfig{});
  EXPECT_EQ(r.stats.failures, 0u);
  EXPECT_EQ(r.stats.frames_processed, d.frames().size());
  EXPECT_GE(r.tracked.size(), d.frames().size() * 9 / 10);
  const auto a = apps::evaluateOdometry(d, r.tracked);
  ASSERT_TRUE(a && a->se3);
  EXPECT_GT(a->se3->path_length_m, 3.0);
  EXPECT_LT(a->se3->ate_rmse_m, 0.03);
  EXPECT_LT(a->se3->ate_rmse_m, 0.01 * a->se3->path_length_m);
  EXPECT_LT(a->gravity_error_first_deg, 1.0);
  EXPECT_LT(a->gravity_error_max_deg, 2.0);
}

TEST_F(VioPipelineSim, MonoGetsItsScaleFromTheImu) {
  const auto d = euroc::EurocDataset::open(session(), euroc::ReaderOptions{1'000'000, false});
  ASSERT_FALSE(d.stereo());
  VioPipelineConfig config;
  config.mono = true;
  const Replay r = replay(d, config);
  EXPECT_EQ(r.stats.failures, 0u);
  EXPECT_GE(r.tracked.size(), d.frames().size() * 8 / 10);
  const auto a = apps::evaluateOdometry(d, r.tracked);
  ASSERT_TRUE(a && a->sim3);
  EXPECT_LT(a->sim3->ate_rmse_m, 0.06);
  EXPECT_NEAR(a->sim3->scale, 1.0, 0.1);
}

TEST_F(VioPipelineSim, BlackoutIsReportedAndTrackingResumesInTheSameWorldFrame) {
  const auto d = euroc::EurocDataset::open(session());
  const std::int64_t from_ns = 5'000'000'000, to_ns = 6'500'000'000;
  VioPipelineConfig config;
  const Replay r = replay(d, config, [&](std::int64_t t, euroc::StereoImages& images) {
    if (t >= from_ns && t < to_ns) {
      std::fill(images.left.pixels.begin(), images.left.pixels.end(), 0);
      std::fill(images.right.pixels.begin(), images.right.pixels.end(), 0);
    }
  });
  ASSERT_GE(r.stats.failures, 1u);
  EXPECT_GE(r.stats.failure_log.front().first, from_ns);
  EXPECT_LE(r.stats.failure_log.front().first, to_ns);
  std::size_t after = 0;
  for (const auto& f : r.tracked) {
    EXPECT_FALSE(f.timestamp_ns > from_ns + 600'000'000 && f.timestamp_ns < to_ns)
        << "a pose was published while blind at " << f.timestamp_ns;
    if (f.segment > 0) ++after;
  }
  EXPECT_GT(after, 50u) << "tracking did not resume after the blackout";
  // One alignment for the whole run: the frame after re-initialisation is the same W (dead
  // reckoning over the gap), so the error stays at the scale of the gap's drift.
  const auto a = apps::evaluateOdometry(d, r.tracked);
  ASSERT_TRUE(a && a->se3);
  EXPECT_LT(a->se3->ate_rmse_m, 0.15);
}

TEST_F(VioPipelineSim, BadSamplesAreCountedAndSkippedAndBadImagesRefused) {
  const auto d = euroc::EurocDataset::open(session());
  VioPipeline pipeline(d.calibration(), VioPipelineConfig{});
  const auto images = d.loadImages(0);
  const std::int64_t t0 = d.frames()[0].timestamp_ns;
  cv::Mat small(120, 188, CV_8UC1, cv::Scalar(0));
  try {
    pipeline.pushFrame(t0, small, cv::Mat(240, 376, CV_8UC1, cv::Scalar(0)));
    FAIL() << "a wrong-size image was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("188x120"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("376x240"), std::string::npos) << e.what();
  }
  EXPECT_THROW(pipeline.pushFrame(t0, images.left, GreyImage()), InputError);  // no right eye
  EXPECT_EQ(pipeline.stats().frames_in, 0u);  // refused frames change nothing

  euroc::ImuSample nan = d.imu()[0];
  nan.accel_mps2.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(pipeline.pushImu(nan).empty());
  EXPECT_EQ(pipeline.stats().imu_nonfinite_skipped, 1u);
  pipeline.pushImu(d.imu()[1]);
  pipeline.pushImu(d.imu()[0]);  // back in time
  EXPECT_EQ(pipeline.stats().imu_out_of_order_skipped, 1u);
  EXPECT_EQ(pipeline.stats().imu_samples, 1u);

  // A frame after the last IMU sample waits; one before it is processed at once.
  const std::int64_t later = d.imu()[1].timestamp_ns + 20'000'000;
  EXPECT_TRUE(pipeline.pushFrame(later, images.left, images.right).empty());
  EXPECT_TRUE(pipeline.pushFrame(later - 1, images.left, images.right).empty());
  EXPECT_EQ(pipeline.stats().frames_out_of_order_skipped, 1u);
  pipeline.flush();
  EXPECT_EQ(pipeline.stats().frames_without_imu_skipped, 1u);
  EXPECT_EQ(pipeline.stats().frames_processed, 0u);
}

TEST_F(VioPipelineSim, OdometryCommandWritesTheTrajectoryAndSummary) {
  apps::OdometryOptions o;
  o.session_dir = session();
  o.out_path = (out_ / "vio.txt").string();
  o.quiet = true;
  ASSERT_EQ(apps::runOdometry(o), 0);
  const auto trajectory = tum::readTrajectory(o.out_path);
  EXPECT_GT(trajectory.size(), 150u);
  std::ifstream summary(out_ / "vio.json");
  const std::string json((std::istreambuf_iterator<char>(summary)),
                         std::istreambuf_iterator<char>());
  EXPECT_NE(json.find("\"frames_tracked\": " + std::to_string(trajectory.size())),
            std::string::npos);
  EXPECT_NE(json.find("\"ate_rmse_m\""), std::string::npos);

  o.mode = "rgbd";
  EXPECT_EQ(apps::runOdometry(o), 2);
  o.mode = "vio";
  o.session_dir = (out_ / "no_such_session").string();
  EXPECT_EQ(apps::runOdometry(o), 2);
}

TEST(VioPipelineEuroc, RealExcerptInitialisesWithGravityAndDriftInBounds) {
  STRATA_REQUIRE_DATA("euroc_v101_micro/mav0", mav0);
  const auto d = euroc::EurocDataset::open(fs::path(mav0).parent_path().string());
  const Replay r = replay(d, VioPipelineConfig{});
  EXPECT_EQ(r.stats.failures, 0u);
  ASSERT_GT(r.tracked.size(), d.frames().size() / 2);
  const auto a = apps::evaluateOdometry(d, r.tracked);
  ASSERT_TRUE(a && a->first);
  EXPECT_LT(a->gravity_error_first_deg, 1.0);
  EXPECT_LT(a->gravity_error_max_deg, 1.0);
  EXPECT_LT(a->first->ate_max_m, 0.02);  // drift from the first pose over the excerpt
}

}  // namespace
}  // namespace strata::odometry

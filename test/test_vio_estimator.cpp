// The sliding-window visual-inertial estimator on synthetic data: simulated trajectory, noisy
// IMU with bias walk and stereo observations with pixel noise.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <random>
#include <vector>

#include "strata/odometry/synthetic/vio_scenario.h"
#include "strata/odometry/vio_estimator.h"
#include "strata/trajectory/trajectory_error.h"

namespace strata::odometry {
namespace {

struct EstimatorRun {
  std::vector<FrameEstimate> estimates;
  std::vector<trajectory::StampedPose> estimated, truth;  // tracked frames: left camera poses
  double worst_up_error_rad = 0.0;                  // gravity direction, tracked frames
  double first_up_error_rad = -1.0;                 // ... at the first tracked frame
  double seconds = 0.0;                             // wall time in addFrame (printed, not asserted)
};

// Feeds IMU and frames from frame `first` on; `corrupt` may change a frame before it is given.
template <typename Corrupt>
EstimatorRun runEstimator(const synthetic::Scenario& s, std::size_t first, const VioConfig& config,
                          Corrupt corrupt) {
  VioEstimator estimator(config, s.rig);
  EstimatorRun run;
  std::size_t next_imu = 0;
  for (std::size_t f = first; f < s.frames.size(); ++f) {
    FrameObservations frame = s.frames[f];
    while (next_imu < s.imu.size() && s.imu[next_imu].t_s <= frame.t_s + 1e-9) {
      estimator.addImu(s.imu[next_imu++]);
    }
    corrupt(f, &frame);
    const auto start = std::chrono::steady_clock::now();
    const FrameEstimate e = estimator.addFrame(frame);
    run.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    run.estimates.push_back(e);
    if (e.status == VioStatus::kTracking) {
      run.estimated.push_back({e.t_s, e.T_W_C});
      run.truth.push_back({e.t_s, s.T_W_C_truth[f]});
      const Eigen::Vector3d up_est = e.T_W_B.linear().transpose() * Eigen::Vector3d::UnitZ();
      const Eigen::Vector3d up_true =
          s.T_W_B_truth[f].linear().transpose() * Eigen::Vector3d::UnitZ();
      if (run.first_up_error_rad < 0.0) {
        run.first_up_error_rad = std::acos(std::min(1.0, up_est.dot(up_true)));
      }
      run.worst_up_error_rad =
          std::max(run.worst_up_error_rad, std::acos(std::min(1.0, up_est.dot(up_true))));
    }
  }
  return run;
}

// Tracked frames of estimates[begin, end): ATE of the left camera positions.
double segmentAte(const synthetic::Scenario& s, std::size_t first, const EstimatorRun& run,
                  double t_begin_s, double t_end_s) {
  std::vector<trajectory::StampedPose> estimated, truth;
  for (std::size_t i = 0; i < run.estimates.size(); ++i) {
    const FrameEstimate& e = run.estimates[i];
    if (e.status != VioStatus::kTracking || e.t_s < t_begin_s || e.t_s >= t_end_s) continue;
    estimated.push_back({e.t_s, e.T_W_C});
    truth.push_back({e.t_s, s.T_W_C_truth[first + i]});
  }
  if (estimated.size() < 3) return 1e9;
  return trajectory::evaluateTrajectory(estimated, truth, trajectory::Alignment::kSE3).ate_rmse_m;
}

// Iterations bound the solves, not time: the tests give the same figures on a loaded machine.
VioConfig deterministicConfig() {
  VioConfig config;
  config.max_solver_time_s = 100.0;
  return config;
}

synthetic::ScenarioConfig biasedScenario() {
  synthetic::ScenarioConfig config;
  config.imu.initial_gyro_bias = Eigen::Vector3d(0.004, -0.006, 0.003);
  config.imu.initial_accel_bias = Eigen::Vector3d(0.03, -0.02, 0.04);
  return config;
}

TEST(VioEstimator, TracksASimulatedStereoSequenceFromStandstill) {
  const synthetic::Scenario s = synthetic::makeScenario(biasedScenario());
  const EstimatorRun run =
      runEstimator(s, 0, deterministicConfig(), [](std::size_t, FrameObservations*) {});
  // Standstill is detected once half a second of IMU is in; every frame after it tracks.
  ASSERT_GE(run.estimates.size(), 200u);
  std::size_t tracked = 0;
  for (const FrameEstimate& e : run.estimates) {
    EXPECT_NE(e.status, VioStatus::kFailed) << e.t_s << ": " << e.reason;
    tracked += e.status == VioStatus::kTracking;
  }
  EXPECT_GE(tracked, run.estimates.size() - 12);
  const trajectory::TrajectoryError error =
      trajectory::evaluateTrajectory(run.estimated, run.truth, trajectory::Alignment::kSE3);
  const double ate = error.ate_rmse_m;
  std::printf("RPE %.3f %% %.4f deg/m over %.2f m\n", error.rpe_trans_percent,
              error.rpe_rot_deg_per_m, error.path_length_m);
  std::printf(
      "standstill start: %zu tracked frames, ATE %.4f m, gravity error %.3f deg at "
      "initialisation, worst %.3f deg, %.1f ms per frame\n",
      tracked, ate, run.first_up_error_rad * 180.0 / M_PI, run.worst_up_error_rad * 180.0 / M_PI,
      1e3 * run.seconds / static_cast<double>(run.estimates.size()));
  EXPECT_LT(ate, 0.02);
  // Standstill initialisation: gravity within 1 degree (the accelerometer bias, unobservable at
  // rest, tilts it by ~0.3 degree here), and it stays there.
  EXPECT_LT(run.first_up_error_rad, 1.0 * M_PI / 180.0);
  EXPECT_LT(run.worst_up_error_rad, 1.0 * M_PI / 180.0);
  // The gyro bias is recovered.
  const FrameEstimate& last = run.estimates.back();
  EXPECT_LT((last.bias.gyro_rad_s - s.imu_truth.back().gyro_bias).norm(), 2e-3);
}

TEST(VioEstimator, InitialisesInMotion) {
  const synthetic::Scenario s = synthetic::makeScenario(biasedScenario());
  const std::size_t first = 60;  // 2 s after the standstill: moving
  const EstimatorRun run =
      runEstimator(s, first, deterministicConfig(), [](std::size_t, FrameObservations*) {});
  std::size_t tracked = 0;
  for (const FrameEstimate& e : run.estimates) {
    EXPECT_NE(e.status, VioStatus::kFailed) << e.t_s << ": " << e.reason;
    tracked += e.status == VioStatus::kTracking;
  }
  EXPECT_GE(tracked, run.estimates.size() - 12);
  const trajectory::TrajectoryError error =
      trajectory::evaluateTrajectory(run.estimated, run.truth, trajectory::Alignment::kSE3);
  const double ate = error.ate_rmse_m;
  std::printf("RPE %.3f %% %.4f deg/m over %.2f m\n", error.rpe_trans_percent,
              error.rpe_rot_deg_per_m, error.path_length_m);
  std::printf(
      "in-motion start: %zu tracked frames, ATE %.4f m, worst gravity error %.3f deg, "
      "%.1f ms per frame\n",
      tracked, ate, run.worst_up_error_rad * 180.0 / M_PI,
      1e3 * run.seconds / static_cast<double>(run.estimates.size()));
  EXPECT_LT(ate, 0.03);
  EXPECT_LT(run.worst_up_error_rad, 2.0 * M_PI / 180.0);
}

TEST(VioEstimator, TracksWithTheLeftCameraAlone) {
  synthetic::Scenario s = synthetic::makeScenario(biasedScenario());
  s.rig.right.reset();
  for (FrameObservations& frame : s.frames) {
    for (FeatureObservation& o : frame.features) o.uv_right_px.reset(), o.xy_right_norm.reset();
  }
  const EstimatorRun run =
      runEstimator(s, 0, deterministicConfig(), [](std::size_t, FrameObservations*) {});
  std::size_t tracked = 0, failed = 0;
  for (const FrameEstimate& e : run.estimates) {
    tracked += e.status == VioStatus::kTracking;
    failed += e.status == VioStatus::kFailed;
    if (e.status == VioStatus::kFailed) std::printf("%.2f s: %s\n", e.t_s, e.reason.c_str());
  }
  const trajectory::TrajectoryError error =
      trajectory::evaluateTrajectory(run.estimated, run.truth, trajectory::Alignment::kSE3);
  std::printf("monocular: %zu tracked, %zu failed, ATE %.4f m, worst gravity error %.3f deg\n",
              tracked, failed, error.ate_rmse_m, run.worst_up_error_rad * 180.0 / M_PI);
  // No stereo scale: the IMU alone makes it metric, an order of magnitude less accurately.
  EXPECT_EQ(failed, 0u);
  EXPECT_GE(tracked, run.estimates.size() - 12);
  EXPECT_LT(error.ate_rmse_m, 0.10);
}

TEST(VioEstimator, ABrokenAccelerometerIsReported) {
  synthetic::Scenario s = synthetic::makeScenario(biasedScenario());
  // From 4 s on the accelerometer reads 30 m/s^2 too much along x (a failed sensor).
  for (ImuMeasurement& m : s.imu) {
    if (m.t_s >= 4.0) m.accel_mps2.x() += 30.0;
  }
  const EstimatorRun run =
      runEstimator(s, 0, deterministicConfig(), [](std::size_t, FrameObservations*) {});
  double failed_at = -1.0;
  std::size_t tracked_after = 0;
  for (const FrameEstimate& e : run.estimates) {
    if (e.status == VioStatus::kFailed && failed_at < 0.0) {
      failed_at = e.t_s;
      std::printf("failure reported at %.2f s: %s\n", e.t_s, e.reason.c_str());
    }
    tracked_after += failed_at > 0.0 && e.status == VioStatus::kTracking;
  }
  EXPECT_GE(failed_at, 4.0);
  EXPECT_LT(failed_at, 4.5);
  // The sensor stays broken: standstill initialisation sees the features move, in-motion
  // alignment finds gravity's magnitude more than 10 % off, so no pose is published again.
  EXPECT_EQ(tracked_after, 0u);
  const double ate_before = segmentAte(s, 0, run, 0.0, failed_at);
  EXPECT_LT(ate_before, 0.02);
}

TEST(VioEstimator, CorruptedObservationsAreReportedAndTrackingRestarts) {
  const synthetic::Scenario s = synthetic::makeScenario(biasedScenario());
  // From 4 s to 5 s the track ids are shuffled: every association is wrong.
  std::mt19937_64 rng(7);
  auto corrupt = [&](std::size_t f, FrameObservations* frame) {
    if (frame->t_s < 4.0 || frame->t_s >= 5.0) return;
    std::vector<std::uint64_t> ids;
    for (const FeatureObservation& o : frame->features) ids.push_back(o.track_id);
    std::shuffle(ids.begin(), ids.end(), rng);
    (void)f;
    for (std::size_t i = 0; i < ids.size(); ++i) frame->features[i].track_id = ids[i];
  };
  const EstimatorRun run = runEstimator(s, 0, deterministicConfig(), corrupt);
  double failed_at = -1.0;
  double tracking_again_at = -1.0;
  for (const FrameEstimate& e : run.estimates) {
    if (e.status == VioStatus::kFailed && failed_at < 0.0) {
      failed_at = e.t_s;
      std::printf("failure reported at %.2f s: %s\n", e.t_s, e.reason.c_str());
      EXPECT_FALSE(e.reason.empty());
    }
    if (failed_at > 0.0 && e.t_s > 5.0 && e.status == VioStatus::kTracking &&
        tracking_again_at < 0) {
      tracking_again_at = e.t_s;
    }
  }
  ASSERT_GE(failed_at, 4.0);
  EXPECT_LT(failed_at, 4.5);
  // No nonsense poses: before the failure, and after re-initialisation (a new world frame).
  const double ate_before = segmentAte(s, 0, run, 0.0, failed_at);
  const double ate_after = segmentAte(s, 0, run, tracking_again_at, 1e9);
  std::printf("ATE before the failure %.4f m, after re-initialisation %.4f m\n", ate_before,
              ate_after);
  EXPECT_LT(ate_before, 0.02);
  EXPECT_LT(ate_after, 0.03);
  // After the corruption ends the estimator re-initialises in motion.
  EXPECT_GT(tracking_again_at, 5.0);
  EXPECT_LT(tracking_again_at, 6.5);
  std::printf("tracking again at %.2f s\n", tracking_again_at);
}

}  // namespace
}  // namespace strata::odometry

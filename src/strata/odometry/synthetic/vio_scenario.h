#pragma once
// Synthetic visual-inertial data for the odometry tests and benchmark: a simulated hand-held
// trajectory (optionally after a standstill), the simulator's IMU model (white noise + bias walk,
// Kalibr's discrete form) and landmarks on the walls of a room projected into a stereo pair with
// pixel noise. No images: the observations are what a perfect front end would report.
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "strata/odometry/camera_rig.h"
#include "strata/odometry/frame_observations.h"
#include "strata/odometry/imu_types.h"
#include "strata/sim/sensors/imu.h"
#include "strata/sim/sensors/camera_path.h"

namespace strata::odometry::synthetic {

struct ScenarioConfig {
  double standstill_s = 1.0;  // the body rests this long before the trajectory starts
  double camera_rate_hz = 20.0;
  double pixel_noise_px = 0.5;
  int max_features = 100;  // per frame, chosen by a fixed per-landmark priority
  int landmarks = 1500;
  sim::ImuConfig imu;  // T_C_B is set from the rig
  std::uint64_t seed = 5;
};

struct Scenario {
  CameraRig rig;
  std::vector<ImuMeasurement> imu;
  std::vector<FrameObservations> frames;
  std::vector<Eigen::Isometry3d> T_W_C_truth;  // per frame, left camera
  std::vector<Eigen::Isometry3d> T_W_B_truth;
  std::vector<Eigen::Vector3d> v_W_B_truth;
  std::vector<sim::ImuSample> imu_truth;  // with the true biases
};

/// The room loop of the sensor tests, ~10 s.
sim::Trajectory roomTrajectory();
/// A stereo rig with EuRoC-like intrinsics, an 11 cm baseline and a rotated, offset IMU.
CameraRig stereoRig();
Scenario makeScenario(const ScenarioConfig& config);

}  // namespace strata::odometry::synthetic

#pragma once
// Sliding-window visual-inertial odometry back end. Each frame handed in becomes a keyframe of a
// window of at most window_size keyframes; each keyframe holds pose q_W_B, p_W_B, velocity and
// IMU biases (state_parameters.h). Factors: IMU preintegration between consecutive keyframes
// (imu_factor.h), stereo/mono reprojection of inverse-depth landmarks anchored in their first
// keyframe under a Huber loss (reprojection_factor.h), and the linear prior left by
// marginalising the oldest keyframe with the landmarks anchored in it (marginalization.h).
// Solved by Ceres' Levenberg-Marquardt with DENSE_SCHUR (landmarks eliminated first), bounded in
// iterations and time.
//
// Lifecycle: kInitializing until standstill (initialization.h (a)) or, in motion, stereo
// visual-only poses of init_frames keyframes aligned with the IMU ((b)); then kTracking. A
// frame whose solve fails a health check reports kFailed with the reason, the window is cleared
// and initialisation starts again with the next frame (no pose is published from a failed solve).
//
// World frame W: z up (gravity -z), origin and yaw where the body was at initialisation.
// Not thread safe: one thread feeds addImu / addFrame.
#include <Eigen/Geometry>
#include <memory>
#include <string>
#include <vector>

#include "strata/odometry/camera_rig.h"
#include "strata/odometry/frame_observations.h"
#include "strata/odometry/imu_types.h"
#include "strata/odometry/initialization.h"

namespace strata::odometry {

struct VioConfig {
  ImuNoise imu;
  double gravity_mps2 = 9.81;
  /// Keyframes in the window: more is smoother and slower (solve time grows about linearly).
  int window_size = 10;
  /// Pixel noise of a feature position, and where the Huber loss turns linear.
  double pixel_sigma_px = 1.0;
  double huber_px = 2.0;
  /// Solver bounds per frame (real time at 20 Hz leaves 50 ms).
  int max_iterations = 6;
  double max_solver_time_s = 0.03;
  /// Re-integrate a preintegration when its bias estimate moved this far from the bias it was
  /// integrated with (the first-order correction is good for small moves only).
  double reintegrate_gyro_bias_rad_s = 0.003;
  double reintegrate_accel_bias_mps2 = 0.05;
  /// Landmark depths accepted at triangulation, and the reprojection error (px) above which an
  /// observation is dropped after a solve.
  double min_depth_m = 0.1;
  double max_depth_m = 60.0;
  double outlier_px = 5.0;

  StandstillConfig standstill;
  /// Keyframes of stereo visual-only poses aligned with the IMU when starting in motion.
  int init_frames = 8;
  /// Prior on the first keyframe. Yaw and position are the gauge (unobservable): held tightly.
  double prior_roll_pitch_rad = 0.01;
  double prior_velocity_mps = 0.02;
  double prior_gyro_bias_rad_s = 0.002;
  double prior_accel_bias_mps2 = 0.1;

  /// Health checks; a violation ends tracking.
  double max_speed_mps = 10.0;
  double max_gyro_bias_rad_s = 0.3;
  double max_accel_bias_mps2 = 2.0;
  double max_median_reprojection_px = 3.0;
  int min_observations = 10;           // in the newest keyframe ...
  int max_frames_without_vision = 10;  // ... for at most this many frames in a row

  /// Throws InputError naming the first bad field.
  void validate() const;
};

enum class VioStatus { kInitializing, kTracking, kFailed };
const char* toString(VioStatus status);

struct FrameEstimate {
  double t_s = 0.0;
  VioStatus status = VioStatus::kInitializing;
  /// Why tracking ended (kFailed) or what initialisation waits for (kInitializing).
  std::string reason;
  /// Valid for kTracking only.
  Eigen::Isometry3d T_W_B = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();  // left camera: T_W_B * T_B_Cl
  Eigen::Vector3d v_W_B = Eigen::Vector3d::Zero();
  ImuBias bias;
  int landmarks = 0;            // landmarks in the solve
  int observations_newest = 0;  // their observations in this frame
  int solver_iterations = 0;
};

class VioEstimator {
 public:
  /// Throws InputError for an invalid config or rig.
  VioEstimator(const VioConfig& config, const CameraRig& rig);
  ~VioEstimator();
  VioEstimator(const VioEstimator&) = delete;
  VioEstimator& operator=(const VioEstimator&) = delete;

  /// Samples in increasing time. Throws InputError for a sample older than the previous one.
  void addImu(const ImuMeasurement& sample);
  /// One camera frame; IMU samples up to at least frame.t_s must have been added. Throws
  /// InputError when they have not, or when frames go back in time.
  FrameEstimate addFrame(const FrameObservations& frame);

  VioStatus status() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace strata::odometry

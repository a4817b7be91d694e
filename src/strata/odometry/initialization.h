#pragma once
// Initial state of the visual-inertial estimator.
//  (a) Standstill: gravity direction from the mean specific force, gyro bias from the mean rate,
//      zero velocity; yaw and position are free and set to zero.
//  (b) In motion: visual-inertial alignment of a short window of metric (stereo) body poses:
//      gyro bias from the relative rotations by linear least squares on dR_ij(bg), then gravity
//      and the velocities from the preintegrated dv, dp by linear least squares, refined with the
//      gravity magnitude known (Qin and Shen, "Robust initialization of monocular visual-inertial
//      estimation on aerial robots", IROS 2017, without the scale for stereo).
#include <Eigen/Geometry>
#include <optional>
#include <vector>

#include "strata/odometry/imu_types.h"
#include "strata/odometry/preintegration.h"

namespace strata::odometry {

struct StandstillConfig {
  /// Samples used: the last window_s of IMU data. Longer: better bias, slower start.
  double window_s = 0.5;
  /// The body counts as still when the per-axis standard deviations stay below these (several
  /// times the sensor noise at 200 Hz, far below hand-held motion).
  double max_gyro_stddev_rad_s = 0.02;
  double max_accel_stddev_mps2 = 0.15;
  /// ... and, where the same tracks are seen window_s apart, their median image motion stays
  /// below this (slow smooth motion can pass the IMU test; 0.5 px pixel noise moves ~1 px).
  double max_feature_motion_px = 2.0;
};

struct InitialState {
  Eigen::Matrix3d R_W_B = Eigen::Matrix3d::Identity();
  Eigen::Vector3d p_W_B = Eigen::Vector3d::Zero();
  Eigen::Vector3d v_W_B = Eigen::Vector3d::Zero();
  ImuBias bias;
};

enum class ImuMotion { kTooFewSamples, kStill, kMoving };
/// Whether the samples with t in [t_end - window_s, t_end] show the body at rest (per-axis
/// standard deviations below the config's bounds); kTooFewSamples when they span under 90 % of
/// the window.
ImuMotion classifyMotion(const std::vector<ImuMeasurement>& samples, double t_end_s,
                         const StandstillConfig& config);

/// Standstill initialisation from samples with t in [t_end - window_s, t_end]. nullopt when the
/// samples do not span the window (90 % of it) or the body moved. World z is up: R_W_B maps the
/// mean specific force onto +z, with the smallest rotation (yaw of B's x kept where possible).
std::optional<InitialState> initializeFromStandstill(const std::vector<ImuMeasurement>& samples,
                                                     double t_end_s,
                                                     const StandstillConfig& config);

struct AlignmentResult {
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_W_V = Eigen::Matrix3d::Identity();  // rotates V so that gravity is -z
  Eigen::Vector3d gravity_V = Eigen::Vector3d::Zero();  // with magnitude gravity_mps2
  std::vector<Eigen::Vector3d> v_V_B;                   // per frame, in V
};

/// In-motion alignment of n >= 3 metric body poses T_V_B (from vision, frame V with unknown
/// gravity) with the n - 1 preintegrations between them. The accelerometer bias is taken as zero
/// (it is nearly inseparable from gravity over a short window). Re-integrates `preintegrations`
/// with the estimated gyro bias. nullopt when the system is degenerate or gravity's magnitude
/// comes out more than 10 % off gravity_mps2 (a sign of bad visual poses).
/// Throws InputError when the sizes do not match.
std::optional<AlignmentResult> alignVisualInertial(const std::vector<Eigen::Isometry3d>& T_V_B,
                                                   std::vector<Preintegration>* preintegrations,
                                                   double gravity_mps2);

/// The smallest rotation taking unit vector a to b.
Eigen::Matrix3d rotationBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b);

}  // namespace strata::odometry

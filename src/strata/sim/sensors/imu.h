#pragma once
// Simulated IMU: accelerometer (specific force) and gyroscope in the body frame from a Trajectory,
// with white noise and bias random walk in the discrete-time form of Kalibr's IMU noise model
// (github.com/ethz-asl/kalibr/wiki/IMU-Noise-Model), written in the EuRoC MAV dataset's CSV layout.
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "strata/sim/sensors/camera_path.h"

namespace strata::sim {

struct ImuConfig {
  double rate_hz = 200.0;
  /// Continuous-time noise densities; defaults: EuRoC's ADIS16448 (sensor.yaml of the dataset).
  double gyro_noise_density = 1.6968e-4;  // rad / s / sqrt(Hz)
  double gyro_random_walk = 1.9393e-5;    // rad / s^2 / sqrt(Hz), bias random walk
  double accel_noise_density = 2.0e-3;    // m / s^2 / sqrt(Hz)
  double accel_random_walk = 3.0e-3;      // m / s^3 / sqrt(Hz), bias random walk
  /// False: exact measurements (initial biases still added).
  bool noise = true;
  Eigen::Vector3d initial_gyro_bias = Eigen::Vector3d::Zero();   // rad / s
  Eigen::Vector3d initial_accel_bias = Eigen::Vector3d::Zero();  // m / s^2
  /// Gravity magnitude; world z is up, g_W = (0, 0, -gravity).
  double gravity_mps2 = 9.81;
  /// Pose of the IMU body frame B in the camera frame C; identity: B = C.
  Eigen::Isometry3d T_C_B = Eigen::Isometry3d::Identity();
  /// Timestamp of trajectory time 0.
  std::int64_t start_time_ns = 0;

  /// Throws InputError naming the first bad field.
  void validate() const;
};

struct ImuSample {
  std::int64_t timestamp_ns = 0;
  double t_s = 0.0;                                      // trajectory time
  Eigen::Vector3d gyro_rad_s = Eigen::Vector3d::Zero();  // measured omega_B
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();  // measured specific force f_B
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // true bias in this sample
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();
};

/// Exact (noise- and bias-free) body rates of a trajectory state: omega_B = R_C_B^T omega_C and
/// f_B = R_W_B^T (a_B_W - g_W), where the body origin's acceleration is
/// a_B_W = a_C_W + R_W_C ([alpha_C]x + [omega_C]x^2) t_C_B.
void idealImu(const TrajectoryState& state, const ImuConfig& config, Eigen::Vector3d* gyro_rad_s,
              Eigen::Vector3d* accel_mps2);

/// Samples at t = k / rate_hz over the whole trajectory. Noise per sample (dt = 1 / rate):
/// z_k = true_k + b_k + sigma / sqrt(dt) n_k, then b_{k+1} = b_k + sigma_b sqrt(dt) n'_k.
/// Same seed, same samples.
std::vector<ImuSample> simulateImu(const Trajectory& trajectory, const ImuConfig& config,
                                   std::uint64_t seed);

/// EuRoC layout (mav0/imu0/data.csv): header
/// "#timestamp [ns],w_RS_S_x [rad s^-1],...,a_RS_S_z [m s^-2]", then one row per sample with
/// 17 significant digits. Written atomically; Error names the path on failure.
void writeImuCsv(const std::string& path, const std::vector<ImuSample>& samples);

}  // namespace strata::sim

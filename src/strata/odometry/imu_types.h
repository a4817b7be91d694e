#pragma once
// IMU samples, noise model and bias of the visual-inertial back end.
#include <Eigen/Core>

namespace strata::odometry {

/// One IMU sample in the body frame B (the IMU's frame).
struct ImuMeasurement {
  double t_s = 0.0;                                      // same clock as the camera frames
  Eigen::Vector3d gyro_rad_s = Eigen::Vector3d::Zero();  // measured angular rate omega_B
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();  // measured specific force f_B
};

/// Continuous-time noise densities (Kalibr's IMU noise model). Defaults: EuRoC's ADIS16448, the
/// same as the simulator's ImuConfig.
struct ImuNoise {
  double gyro_noise_density = 1.6968e-4;  // rad / s / sqrt(Hz)
  double gyro_random_walk = 1.9393e-5;    // rad / s^2 / sqrt(Hz)
  double accel_noise_density = 2.0e-3;    // m / s^2 / sqrt(Hz)
  double accel_random_walk = 3.0e-3;      // m / s^3 / sqrt(Hz)

  /// Throws InputError naming the first negative or non-finite field.
  void validate() const;
};

/// Additive sensor biases: measured = true + bias + noise.
struct ImuBias {
  Eigen::Vector3d gyro_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
};

}  // namespace strata::odometry

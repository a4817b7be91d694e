#pragma once
// What an EuRoC/ASL session folder holds (io/euroc_dataset.h reads it): calibration, IMU samples,
// stereo (or mono) frames, ground truth, and the counts of what the reader dropped or repaired.
//
// Frames (EuRoC convention, Burri et al. IJRR 2016):
//   B  body = the IMU frame (imu0's T_BS is identity in EuRoC and in Strata's simulator).
//   S  a sensor: cam0 (left), cam1 (right), imu0. Camera axes: x right, y down, z along the view.
//   W  the ground-truth world frame, z up (gravity along -z).
// T_B_S = sensor.yaml's T_BS: maps points in sensor coordinates to body coordinates
// (p_B = T_B_S p_S), i.e. the sensor's pose in the body frame.
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace strata::euroc {

enum class DistortionModel {
  kNone,              // no coefficients (e.g. rectified or simulated images)
  kRadialTangential,  // OpenCV plumb_bob: k1 k2 p1 p2
  kEquidistant,       // Kannala-Brandt fisheye: k1 k2 k3 k4
};

/// One camera of the rig, as its sensor.yaml states it (images are NOT undistorted by the reader).
struct CameraCalibration {
  std::string name;  // "cam0", "cam1"
  int width_px = 0;  // resolution: [width, height]
  int height_px = 0;
  double fu_px = 0.0;  // intrinsics: [fu, fv, cu, cv]; pixel centres at integer coordinates
  double fv_px = 0.0;
  double cu_px = 0.0;
  double cv_px = 0.0;
  DistortionModel distortion = DistortionModel::kNone;
  std::array<double, 4> distortion_coefficients{};  // zeros for kNone
  double rate_hz = 0.0;
  Eigen::Isometry3d T_B_C = Eigen::Isometry3d::Identity();  // camera pose in the body frame
};

/// imu0's sensor.yaml: rates and Kalibr's continuous-time noise model.
struct ImuCalibration {
  double rate_hz = 0.0;
  double gyro_noise_density = 0.0;                          // rad / s / sqrt(Hz)
  double gyro_random_walk = 0.0;                            // rad / s^2 / sqrt(Hz)
  double accel_noise_density = 0.0;                         // m / s^2 / sqrt(Hz)
  double accel_random_walk = 0.0;                           // m / s^3 / sqrt(Hz)
  Eigen::Isometry3d T_B_I = Eigen::Isometry3d::Identity();  // IMU pose in the body frame
};

struct Calibration {
  /// [cam0] (mono) or [cam0, cam1] (stereo).
  std::vector<CameraCalibration> cameras;
  ImuCalibration imu;
  bool stereo() const { return cameras.size() == 2; }
  /// Right camera's pose in the left camera's frame: T_B_C0^-1 T_B_C1 (stereo only).
  Eigen::Isometry3d T_C0_C1() const { return cameras.at(0).T_B_C.inverse() * cameras.at(1).T_B_C; }
};

/// One IMU sample in the IMU frame: gyro omega (rad/s) and specific force (accel - gravity, m/s^2).
struct ImuSample {
  std::int64_t timestamp_ns = 0;
  Eigen::Vector3d gyro_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
};

/// One camera frame: the left image and, for stereo, the right one with the same timestamp.
struct StereoFrame {
  std::int64_t timestamp_ns = 0;
  std::string left_path;   // absolute or relative to the working directory, as opened
  std::string right_path;  // "" for mono
};

/// One ground-truth state. Velocity and biases only when has_velocity_and_biases (EuRoC's
/// state_groundtruth_estimate0, not the TUM files).
struct GroundTruthState {
  std::int64_t timestamp_ns = 0;
  Eigen::Isometry3d T_W_B = Eigen::Isometry3d::Identity();  // body-to-world
  bool has_velocity_and_biases = false;
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();  // m/s
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // rad/s
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // m/s^2
};

/// What the reader counted while opening (nothing here is an error; see euroc_dataset.h).
struct ReaderStats {
  std::size_t imu_rows = 0;               // data rows in imu0/data.csv
  std::size_t imu_nonfinite_skipped = 0;  // rows with a NaN/inf value, dropped
  std::size_t imu_gaps = 0;               // intervals over 1.5 nominal periods
  std::size_t imu_missing_samples = 0;    // samples those gaps lack at rate_hz
  std::size_t left_frames = 0;            // cam0/data.csv rows whose image exists
  std::size_t right_frames = 0;           // cam1/data.csv rows whose image exists (0 for mono)
  std::size_t missing_images = 0;         // data.csv rows (both cameras) whose image is absent
  std::string first_missing_image;        // the first such path, for messages
  std::size_t stereo_pairs = 0;           // frames() of a stereo session
  std::size_t unpaired_left = 0;          // cam0 rows with no cam1 row within the tolerance
  std::size_t unpaired_right = 0;         // cam1 rows with no cam0 row within the tolerance
  std::size_t ground_truth_states = 0;
};

/// One entry of the time-ordered replay stream: an IMU sample or a camera frame, by index.
struct Event {
  enum class Kind { kImu, kFrame };
  std::int64_t timestamp_ns = 0;
  Kind kind = Kind::kImu;
  std::size_t index = 0;  // into imu() or frames()
};

}  // namespace strata::euroc

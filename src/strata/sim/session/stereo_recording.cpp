#include "strata/sim/session/stereo_recording.h"

#include <cmath>
#include <filesystem>

#include "strata/core/error.h"
#include "strata/io/euroc_writer.h"
#include "strata/sim/rng.h"

namespace strata::sim {
namespace {

constexpr std::uint64_t kStereoStream = 0x73746572;  // "ster": frame seeds of the grey camera

std::vector<double> cameraTimes(const SimSessionDataset& session,
                                const StereoRecordingConfig& config) {
  std::vector<double> times;
  for (double t : session.trajectory().sampleTimes(config.camera_rate_hz)) {
    if (config.duration_s > 0.0 && t > config.duration_s + 1e-9) break;
    times.push_back(t);
  }
  return times;
}

std::int64_t toNs(double t_s, std::int64_t start_ns) { return start_ns + std::llround(t_s * 1e9); }

GreyCameraConfig greyConfig(const StereoRecordingConfig& config) {
  GreyCameraConfig grey;
  const euroc::CameraCalibration cam0 = stereoCalibration(config).cameras.at(0);
  grey.intrinsics.width_px = cam0.width_px;
  grey.intrinsics.height_px = cam0.height_px;
  grey.intrinsics.fx_px = static_cast<float>(cam0.fu_px);
  grey.intrinsics.fy_px = static_cast<float>(cam0.fv_px);
  grey.intrinsics.cx_px = static_cast<float>(cam0.cu_px);
  grey.intrinsics.cy_px = static_cast<float>(cam0.cv_px);
  grey.baseline_m = config.stereo ? config.baseline_m : 0.0;
  grey.pixel_noise_sigma = config.pixel_noise_sigma;
  grey.exposure_gain_sigma = config.exposure_gain_sigma;
  grey.exposure_offset_sigma = config.exposure_offset_sigma;
  grey.threads = config.threads;
  return grey;
}

/// Body state from the camera's: T_W_B = T_W_C T_C_B; the body origin moves with
/// v_B = v_C + R_W_C (omega_C x t_C_B).
euroc::GroundTruthState bodyState(const TrajectoryState& state, const ImuSample& sample,
                                  const Eigen::Isometry3d& T_C_B) {
  euroc::GroundTruthState truth;
  truth.timestamp_ns = sample.timestamp_ns;
  truth.T_W_B = state.T_W_C * T_C_B;
  truth.has_velocity_and_biases = true;
  truth.velocity_W =
      state.velocity_W + state.T_W_C.linear() * state.angular_velocity_C.cross(T_C_B.translation());
  truth.gyro_bias = sample.gyro_bias;
  truth.accel_bias = sample.accel_bias;
  return truth;
}

}  // namespace

Eigen::Isometry3d defaultT_C_B() {
  Eigen::Matrix3d R_C_B;  // columns: the body's x (forward), y (left), z (up) in camera axes
  R_C_B.col(0) = Eigen::Vector3d(0, 0, 1);
  R_C_B.col(1) = Eigen::Vector3d(-1, 0, 0);
  R_C_B.col(2) = Eigen::Vector3d(0, -1, 0);
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R_C_B;
  T.translation() = Eigen::Vector3d(0.055, 0.01, -0.02);  // near the middle of the 11 cm pair
  return T;
}

ImuConfig StereoRecordingConfig::defaultImuConfig() {
  ImuConfig imu;
  imu.T_C_B = defaultT_C_B();
  return imu;
}

void StereoRecordingConfig::validate() const {
  if (width_px < 8 || height_px < 8) throw InputError("stereo recording: image under 8x8 pixels");
  if (!(focal_px >= 0.0) || !std::isfinite(focal_px)) {
    throw InputError("stereo recording: focal_px must be finite and >= 0 (0 = 0.61 * width)");
  }
  if (stereo && (!(baseline_m > 0.0) || !std::isfinite(baseline_m))) {
    throw InputError("stereo recording: baseline_m must be positive");
  }
  if (!(camera_rate_hz > 0.0) || !std::isfinite(camera_rate_hz)) {
    throw InputError("stereo recording: camera_rate_hz must be positive");
  }
  if (!(duration_s >= 0.0) || !std::isfinite(duration_s)) {
    throw InputError("stereo recording: duration_s must be finite and >= 0 (0 = whole path)");
  }
  imu.validate();
  greyConfig(*this).validate();
}

euroc::Calibration stereoCalibration(const StereoRecordingConfig& config) {
  euroc::Calibration calibration;
  euroc::CameraCalibration cam0;
  cam0.name = "cam0";
  cam0.width_px = config.width_px;
  cam0.height_px = config.height_px;
  cam0.fu_px = cam0.fv_px = config.focal_px > 0.0 ? config.focal_px : 0.61 * config.width_px;
  cam0.cu_px = 0.5 * (config.width_px - 1);
  cam0.cv_px = 0.5 * (config.height_px - 1);
  cam0.rate_hz = config.camera_rate_hz;
  cam0.T_B_C = config.imu.T_C_B.inverse();
  calibration.cameras.push_back(cam0);
  if (config.stereo) {
    euroc::CameraCalibration cam1 = cam0;
    cam1.name = "cam1";
    cam1.T_B_C = cam0.T_B_C * Eigen::Translation3d(config.baseline_m, 0.0, 0.0);
    calibration.cameras.push_back(cam1);
  }
  calibration.imu.rate_hz = config.imu.rate_hz;
  const bool noise = config.imu.noise;
  calibration.imu.gyro_noise_density = noise ? config.imu.gyro_noise_density : 0.0;
  calibration.imu.gyro_random_walk = noise ? config.imu.gyro_random_walk : 0.0;
  calibration.imu.accel_noise_density = noise ? config.imu.accel_noise_density : 0.0;
  calibration.imu.accel_random_walk = noise ? config.imu.accel_random_walk : 0.0;
  return calibration;
}

std::size_t stereoFrameCount(const SimSessionDataset& session,
                             const StereoRecordingConfig& config) {
  return cameraTimes(session, config).size();
}

StereoRecording::StereoRecording(const SimSessionDataset& session,
                                 const StereoRecordingConfig& config)
    : session_(session), config_(config) {
  config_.validate();
  calibration_ = stereoCalibration(config_);
  camera_ = std::make_unique<GreyCamera>(greyConfig(config_));
  frame_times_s_ = cameraTimes(session_, config_);
  for (double t : frame_times_s_) frame_ns_.push_back(toNs(t, config_.imu.start_time_ns));
  for (const ImuSample& s : session_.imu(config_.imu)) {
    if (config_.duration_s > 0.0 && s.t_s > config_.duration_s + 1e-9) break;
    imu_.push_back({s.timestamp_ns, s.gyro_rad_s, s.accel_mps2});
    truth_.push_back(bodyState(session_.trajectory().state(s.t_s), s, config_.imu.T_C_B));
  }
}

StereoRecording::~StereoRecording() = default;

GreyFrame StereoRecording::renderFrame(std::size_t k) const {
  const std::uint64_t seed = hashCombine(session_.seed(), kStereoStream);
  return camera_->render(session_.scene(), session_.trajectory().pose(frame_times_s_.at(k)),
                         session_.lighting(), hashCombine(seed, k));
}

double StereoRecording::duration_s() const {
  return frame_times_s_.empty() ? 0.0 : frame_times_s_.back() - frame_times_s_.front();
}

StereoRecordingSummary writeStereoRecording(const SimSessionDataset& session,
                                            const StereoRecordingConfig& config,
                                            const std::string& folder,
                                            const std::function<void()>& on_frame) {
  const StereoRecording recording(session, config);
  euroc::EurocWriter writer(folder, recording.calibration());
  const std::vector<std::int64_t>& frame_ns = recording.frameTimestamps();
  for (std::size_t k = 0; k < frame_ns.size(); ++k) {
    const GreyFrame frame = recording.renderFrame(k);
    writer.addFrame(frame_ns[k], frame.eyes[0], config.stereo ? frame.eyes[1] : GreyImage());
    if (on_frame) on_frame();
  }
  writer.finish(recording.imu(), recording.groundTruth());
  euroc::writeGroundTruthTum((std::filesystem::path(folder) / "groundtruth_body.txt").string(),
                             recording.groundTruth());
  StereoRecordingSummary summary;
  summary.frames = frame_ns.size();
  summary.imu_samples = recording.imu().size();
  summary.duration_s = recording.duration_s();
  return summary;
}

}  // namespace strata::sim

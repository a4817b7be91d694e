#include "strata/core/clock.h"
#include "strata/odometry/pipeline/vio_pipeline.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "strata/core/error.h"
#include "strata/odometry/so3.h"

namespace strata::odometry {
namespace {

// IMU kept for the gyro prediction and for dead reckoning over a re-initialisation.
constexpr std::int64_t kImuHistoryNs = 10'000'000'000;
// Longest gap between tracking segments bridged by dead reckoning (see bridgeGap).
constexpr double kMaxDeadReckoning_s = 3.0;

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

DistortionModel toFrontend(euroc::DistortionModel model) {
  switch (model) {
    case euroc::DistortionModel::kRadialTangential:
      return DistortionModel::kRadialTangential;
    case euroc::DistortionModel::kEquidistant:
      return DistortionModel::kEquidistant;
    case euroc::DistortionModel::kNone:
      break;
  }
  return DistortionModel::kNone;
}

PinholeIntrinsics pinhole(const euroc::CameraCalibration& c) {
  PinholeIntrinsics p;
  p.fx_px = c.fu_px;
  p.fy_px = c.fv_px;
  p.cx_px = c.cu_px;
  p.cy_px = c.cv_px;
  p.width_px = c.width_px;
  p.height_px = c.height_px;
  return p;
}

// The rotation about z (world up) closest to R in the xy block, as an isometry with translation
// taking p_from to p_to: maps a gravity-aligned frame onto another keeping gravity.
Eigen::Isometry3d yawAndPosition(const Eigen::Isometry3d& T_to, const Eigen::Isometry3d& T_from) {
  const Eigen::Matrix3d R = T_to.linear() * T_from.linear().transpose();
  const double yaw = std::atan2(R(1, 0) - R(0, 1), R(0, 0) + R(1, 1));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = T_to.translation() - T.linear() * T_from.translation();
  return T;
}

bool allPositive(const ImuNoise& n) {
  return n.gyro_noise_density > 0 && n.gyro_random_walk > 0 && n.accel_noise_density > 0 &&
         n.accel_random_walk > 0;
}

}  // namespace

void VioPipelineConfig::validate() const {
  frontend.validate();
  backend.validate();
  if (max_pending_frames < 1) {
    throw InputError("VioPipelineConfig: max_pending_frames must be at least 1");
  }
}

Camera frontendCamera(const euroc::CameraCalibration& c) {
  Camera camera;
  camera.width_px = c.width_px;
  camera.height_px = c.height_px;
  camera.fx_px = c.fu_px;
  camera.fy_px = c.fv_px;
  camera.cx_px = c.cu_px;
  camera.cy_px = c.cv_px;
  camera.distortion = toFrontend(c.distortion);
  camera.coefficients = c.distortion_coefficients;
  camera.T_B_C = c.T_B_C;
  camera.name = c.name.empty() ? std::string("camera") : c.name;
  return camera;
}

CameraRig backendRig(const euroc::Calibration& calibration, bool mono) {
  if (calibration.cameras.empty()) throw InputError("VIO: the calibration has no camera");
  CameraRig rig;
  rig.left = pinhole(calibration.cameras[0]);
  rig.T_B_Cl = calibration.cameras[0].T_B_C;
  if (!mono && calibration.cameras.size() > 1) {
    rig.right = pinhole(calibration.cameras[1]);
    rig.T_B_Cr = calibration.cameras[1].T_B_C;
  }
  return rig;
}

VioPipeline::VioPipeline(const euroc::Calibration& calibration, VioPipelineConfig config)
    : config_(std::move(config)) {
  if (config_.use_calibration_noise) {
    ImuNoise noise;
    noise.gyro_noise_density = calibration.imu.gyro_noise_density;
    noise.gyro_random_walk = calibration.imu.gyro_random_walk;
    noise.accel_noise_density = calibration.imu.accel_noise_density;
    noise.accel_random_walk = calibration.imu.accel_random_walk;
    // A noise-free simulation states zeros: the estimator's defaults stand in for them.
    if (allPositive(noise)) config_.backend.imu = noise;
  }
  config_.validate();
  rig_ = backendRig(calibration, config_.mono);
  left_camera_ = frontendCamera(calibration.cameras[0]);
  left_camera_.validate();
  if (rig_.right) {
    right_camera_ = frontendCamera(calibration.cameras[1]);
    tracker_ = std::make_unique<FeatureTracker>(StereoCamera{left_camera_, right_camera_},
                                                config_.frontend);
  } else {
    tracker_ = std::make_unique<FeatureTracker>(left_camera_, config_.frontend);
  }
  T_B_I_ = calibration.imu.T_B_I;
  estimator_ = std::make_unique<VioEstimator>(config_.backend, rig_);
}

VioPipeline::~VioPipeline() = default;

std::string imuOutOfRangeWarning(std::size_t skipped) {
  if (skipped == 0) return "";
  char text[240];
  std::snprintf(text, sizeof(text),
                "%zu IMU samples beyond any IMU's range (|gyro| > %.0f rad/s or |accel| > %.0f "
                "m/s^2) were skipped: are the IMU's units or scale wrong?",
                skipped, kMaxImuAngularRate_rad_s, kMaxImuAcceleration_mps2);
  return text;
}

VioStatus VioPipeline::status() const { return estimator_->status(); }

double VioPipeline::seconds(std::int64_t timestamp_ns) const {
  return 1e-9 * static_cast<double>(timestamp_ns - *epoch_ns_);
}

std::vector<PipelineFrame> VioPipeline::pushImu(const euroc::ImuSample& sample) {
  if (!finite(sample.gyro_rad_s) || !finite(sample.accel_mps2)) {
    ++stats_.imu_nonfinite_skipped;
    return {};
  }
  if (sample.gyro_rad_s.norm() > kMaxImuAngularRate_rad_s ||
      sample.accel_mps2.norm() > kMaxImuAcceleration_mps2) {
    ++stats_.imu_out_of_range_skipped;
    return {};
  }
  if (!imu_.empty() && sample.timestamp_ns <= imu_.back().timestamp_ns) {
    ++stats_.imu_out_of_order_skipped;
    return {};
  }
  // The epoch is a second before the first timestamp of either stream, so that the other
  // stream's first timestamps stay positive (never moved afterwards: the estimator keeps times).
  if (!epoch_ns_) epoch_ns_ = sample.timestamp_ns - 1'000'000'000;
  euroc::ImuSample body = sample;
  body.gyro_rad_s = T_B_I_.linear() * sample.gyro_rad_s;
  body.accel_mps2 = T_B_I_.linear() * sample.accel_mps2;
  imu_.push_back(body);
  while (imu_.size() > 2 && imu_.front().timestamp_ns < body.timestamp_ns - kImuHistoryNs) {
    imu_.pop_front();
  }
  ++stats_.imu_samples;
  estimator_->addImu({seconds(body.timestamp_ns), body.gyro_rad_s, body.accel_mps2});
  return drain();
}

void VioPipeline::checkImage(const cv::Mat& image, const Camera& camera, const char* eye) const {
  if (image.empty()) throw InputError(std::string("VIO: the ") + eye + " image is empty");
  if (image.type() != CV_8UC1) {
    throw InputError(std::string("VIO: the ") + eye + " image is not 8-bit grey");
  }
  if (image.cols != camera.width_px || image.rows != camera.height_px) {
    throw InputError(std::string("VIO: the ") + eye + " image is " + std::to_string(image.cols) +
                     "x" + std::to_string(image.rows) + " px but " + camera.name +
                     " is calibrated for " + std::to_string(camera.width_px) + "x" +
                     std::to_string(camera.height_px) + " px");
  }
}

std::vector<PipelineFrame> VioPipeline::pushFrame(std::int64_t timestamp_ns, const cv::Mat& left,
                                                  const cv::Mat& right) {
  checkImage(left, left_camera_, "left");
  if (rig_.right) checkImage(right, right_camera_, "right");
  ++stats_.frames_in;
  const std::optional<std::int64_t> previous =
      pending_.empty() ? last_frame_ns_ : std::optional<std::int64_t>(pending_.back().timestamp_ns);
  if (previous && timestamp_ns <= *previous) {
    ++stats_.frames_out_of_order_skipped;
    return {};
  }
  if (!epoch_ns_) epoch_ns_ = timestamp_ns - 1'000'000'000;
  pending_.push_back({timestamp_ns, left.clone(), rig_.right ? right.clone() : cv::Mat()});
  while (static_cast<int>(pending_.size()) > config_.max_pending_frames) {
    pending_.pop_front();
    ++stats_.frames_without_imu_skipped;
  }
  return drain();
}

void VioPipeline::flush() {
  stats_.frames_without_imu_skipped += pending_.size();
  pending_.clear();
}

std::vector<PipelineFrame> VioPipeline::drain() {
  std::vector<PipelineFrame> out;
  while (!pending_.empty() && !imu_.empty() &&
         imu_.back().timestamp_ns >= pending_.front().timestamp_ns) {
    // pushFrame queued it only after the previous one: no order check is left to do here.
    const Pending frame = std::move(pending_.front());
    pending_.pop_front();
    out.push_back(process(frame));
  }
  return out;
}

std::size_t VioPipeline::firstImuCovering(std::int64_t t_ns) const {
  // The last sample at or before t (the history holds up to 10 s, a frame needs 50 ms of it).
  const auto after = std::upper_bound(
      imu_.begin(), imu_.end(), t_ns,
      [](std::int64_t t, const euroc::ImuSample& sample) { return t < sample.timestamp_ns; });
  return after == imu_.begin() ? 0 : static_cast<std::size_t>(after - imu_.begin()) - 1;
}

std::vector<PipelineFrame> VioPipeline::pushFrame(std::int64_t timestamp_ns, const GreyImage& left,
                                                  const GreyImage& right) {
  const auto view = [](const GreyImage& image) {
    return image.empty() ? cv::Mat()
                         : cv::Mat(image.height_px, image.width_px, CV_8UC1,
                                   const_cast<std::uint8_t*>(image.pixels.data()));
  };
  return pushFrame(timestamp_ns, view(left), view(right));  // copied when queued
}

std::optional<Eigen::Matrix3d> VioPipeline::predictCameraRotation(std::int64_t from_ns,
                                                                  std::int64_t to_ns) {
  if (imu_.empty() || imu_.front().timestamp_ns > from_ns) return std::nullopt;
  // R_Bkm1_Bk by integrating the bias-corrected rate over [from, to], sample-held.
  Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
  for (std::size_t i = firstImuCovering(from_ns); i + 1 < imu_.size(); ++i) {
    const std::int64_t a = std::max(imu_[i].timestamp_ns, from_ns);
    const std::int64_t b = std::min(imu_[i + 1].timestamp_ns, to_ns);
    if (b <= a) continue;
    const Eigen::Vector3d w =
        0.5 * (imu_[i].gyro_rad_s + imu_[i + 1].gyro_rad_s) - bias_.gyro_rad_s;
    R = R * expSO3(w * 1e-9 * static_cast<double>(b - a));
  }
  return cameraRotation(R.transpose(), left_camera_.T_B_C);
}

Eigen::Isometry3d VioPipeline::deadReckon(std::int64_t to_ns) const {
  const LastState& s = *last_tracked_;
  Eigen::Matrix3d R = s.T_W_B.linear();
  Eigen::Vector3d p = s.T_W_B.translation();
  Eigen::Vector3d v = s.v_W_B;
  const Eigen::Vector3d g(0.0, 0.0, -config_.backend.gravity_mps2);
  for (std::size_t i = firstImuCovering(s.timestamp_ns); i + 1 < imu_.size(); ++i) {
    const std::int64_t a = std::max(imu_[i].timestamp_ns, s.timestamp_ns);
    const std::int64_t b = std::min(imu_[i + 1].timestamp_ns, to_ns);
    if (b <= a) continue;
    const double dt = 1e-9 * static_cast<double>(b - a);
    const Eigen::Vector3d w =
        0.5 * (imu_[i].gyro_rad_s + imu_[i + 1].gyro_rad_s) - bias_.gyro_rad_s;
    const Eigen::Vector3d f =
        0.5 * (imu_[i].accel_mps2 + imu_[i + 1].accel_mps2) - bias_.accel_mps2;
    const Eigen::Vector3d a_W = R * f + g;
    p += v * dt + 0.5 * a_W * dt * dt;
    v += a_W * dt;
    R = R * expSO3(w * dt);
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R;
  T.translation() = p;
  return T;
}

Eigen::Isometry3d VioPipeline::bridgeGap(std::int64_t to_ns) {
  Eigen::Isometry3d T_W_B = deadReckon(to_ns);
  const double gap_s = 1e-9 * static_cast<double>(to_ns - last_tracked_->timestamp_ns);
  const double speed_mps =
      (T_W_B.translation() - last_tracked_->T_W_B.translation()).norm() / std::max(gap_s, 1e-3);
  // Double integration of the accelerometer is only good for short gaps; one that implies an
  // impossible speed (the failure that ended tracking may have been the IMU's) is not trusted:
  // the position is held where tracking ended, the gyro's rotation stands.
  if (gap_s > kMaxDeadReckoning_s || speed_mps > config_.backend.max_speed_mps) {
    T_W_B.translation() = last_tracked_->T_W_B.translation();
    ++stats_.reanchored_position_held;
  } else {
    ++stats_.reanchored_dead_reckoned;
  }
  return T_W_B;
}

PipelineFrame VioPipeline::process(const Pending& frame) {
  PipelineFrame out;
  out.timestamp_ns = frame.timestamp_ns;
  std::optional<Eigen::Matrix3d> R_Ck_Ckm1;
  if (last_frame_ns_) R_Ck_Ckm1 = predictCameraRotation(*last_frame_ns_, frame.timestamp_ns);
  last_frame_ns_ = frame.timestamp_ns;

  auto start = std::chrono::steady_clock::now();
  const FrameFeatures features =
      tracker_->process(frame.timestamp_ns, frame.left, frame.right, R_Ck_Ckm1);
  out.frontend_ms = msSince(start);
  out.features = static_cast<int>(features.features.size());
  out.stereo_matched = features.stats.stereo_matched;
  out.frontend_lost = features.stats.lost;

  start = std::chrono::steady_clock::now();
  const FrameEstimate e =
      estimator_->addFrame(FrameObservations{seconds(frame.timestamp_ns), features.features});
  out.backend_ms = msSince(start);
  stats_.frontend_ms_total += out.frontend_ms;
  stats_.backend_ms_total += out.backend_ms;
  ++stats_.frames_processed;

  out.status = e.status;
  out.reason = e.reason;
  out.landmarks = e.landmarks;
  out.segment = segment_;
  switch (e.status) {
    case VioStatus::kTracking: {
      bias_ = e.bias;
      if (!anchored_) {
        if (last_tracked_) {
          T_W_E_ = yawAndPosition(bridgeGap(frame.timestamp_ns), e.T_W_B);
        } else if (config_.anchor_W_B) {
          const auto truth = config_.anchor_W_B(frame.timestamp_ns);
          if (truth) T_W_E_ = yawAndPosition(*truth, e.T_W_B);
        }
        anchored_ = true;
      }
      out.T_W_B = T_W_E_ * e.T_W_B;
      out.T_W_C = out.T_W_B * rig_.T_B_Cl;
      out.v_W_B = T_W_E_.linear() * e.v_W_B;
      out.bias = e.bias;
      last_tracked_ = LastState{frame.timestamp_ns, out.T_W_B, out.v_W_B};
      ++stats_.frames_tracking;
      if (stats_.first_tracking_ns < 0) stats_.first_tracking_ns = frame.timestamp_ns;
      break;
    }
    case VioStatus::kFailed:
      ++stats_.failures;
      stats_.failure_log.emplace_back(frame.timestamp_ns, e.reason);
      anchored_ = false;
      ++segment_;
      break;
    case VioStatus::kInitializing:
      ++stats_.frames_initializing;
      break;
  }
  return out;
}

}  // namespace strata::odometry

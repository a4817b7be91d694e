#include "strata/odometry/vio_estimator.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>
#include <string>
#include <unordered_map>

#include "strata/core/error.h"
#include "strata/odometry/internal/vio_window.h"

namespace strata::odometry {

using internal::Factor;
using internal::FactorKind;
using internal::Keyframe;

const char* toString(VioStatus status) {
  switch (status) {
    case VioStatus::kInitializing:
      return "initializing";
    case VioStatus::kTracking:
      return "tracking";
    case VioStatus::kFailed:
      return "failed";
  }
  return "?";
}

void VioConfig::validate() const {
  imu.validate();
  auto positive = [](double v, const char* field) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw InputError(std::string("VioConfig: ") + field + " must be positive and finite");
    }
  };
  positive(gravity_mps2, "gravity_mps2");
  positive(pixel_sigma_px, "pixel_sigma_px");
  positive(huber_px, "huber_px");
  positive(max_solver_time_s, "max_solver_time_s");
  positive(min_depth_m, "min_depth_m");
  positive(outlier_px, "outlier_px");
  positive(prior_roll_pitch_rad, "prior_roll_pitch_rad");
  positive(prior_velocity_mps, "prior_velocity_mps");
  positive(prior_gyro_bias_rad_s, "prior_gyro_bias_rad_s");
  positive(prior_accel_bias_mps2, "prior_accel_bias_mps2");
  if (!(max_depth_m > min_depth_m))
    throw InputError("VioConfig: max_depth_m must exceed min_depth_m");
  if (window_size < 2) throw InputError("VioConfig: window_size must be at least 2");
  if (max_iterations < 1) throw InputError("VioConfig: max_iterations must be at least 1");
  if (init_frames < 3) throw InputError("VioConfig: init_frames must be at least 3");
}

struct VioEstimator::Impl {
  Impl(const VioConfig& c, const CameraRig& r)
      : config(c), rig(r), window(r, c.huber_px / c.pixel_sigma_px) {}

  VioConfig config;
  CameraRig rig;
  internal::Window window;
  std::vector<ImuMeasurement> imu;
  VioStatus status = VioStatus::kInitializing;
  std::int64_t next_id = 0;
  double last_frame_t_s = -1e300;
  std::deque<FrameObservations> recent_frames;  // the last standstill.window_s of frames
  int frames_without_vision = 0;

  internal::SolveSettings settings(bool visual_only) const {
    internal::SolveSettings s;
    s.pixel_sigma_px = config.pixel_sigma_px;
    s.huber_px = config.huber_px;
    s.max_iterations = config.max_iterations;
    s.max_solver_time_s = config.max_solver_time_s;
    s.gravity_W = Eigen::Vector3d(0.0, 0.0, -config.gravity_mps2);
    s.visual_only = visual_only;
    return s;
  }

  Keyframe& pushKeyframe(double t_s) {
    Keyframe k;
    k.id = next_id++;
    k.t_s = t_s;
    if (!window.keyframes.empty()) {
      const Keyframe& prev = window.keyframes.back();
      k.from_previous = std::make_shared<Preintegration>(prev.bias(), config.imu);
      k.from_previous->integrateInterval(imu, prev.t_s, t_s);
      Eigen::Matrix3d R;
      Eigen::Vector3d p, v;
      const Eigen::Isometry3d T = prev.T_W_B();
      k.from_previous->predict(T.linear(), T.translation(), prev.velocity(), prev.bias(),
                               settings(false).gravity_W, &R, &p, &v);
      k.setPose(R, p);
      std::copy(prev.speed_bias, prev.speed_bias + kSpeedBiasSize, k.speed_bias);
      for (int i = 0; i < 3; ++i) k.speed_bias[i] = v[i];
    }
    window.keyframes.push_back(k);
    return window.keyframes.back();
  }

  void setFirstPrior(double roll_pitch_rad, double velocity_mps) {
    Keyframe& k = window.keyframes.front();
    Eigen::VectorXd sigmas(kPoseTangentSize + kSpeedBiasSize);
    // Ceres' quaternion increment is half the rotation vector, in the world frame.
    const double gauge = 1e-4;
    sigmas << 0.5 * roll_pitch_rad, 0.5 * roll_pitch_rad, 0.5 * gauge, gauge, gauge, gauge,
        Eigen::Vector3d::Constant(velocity_mps),
        Eigen::Vector3d::Constant(config.prior_gyro_bias_rad_s),
        Eigen::Vector3d::Constant(config.prior_accel_bias_mps2);
    window.prior = makeDiagonalPrior(
        {{k.pose, kPoseSize, window.poseManifold()}, {k.speed_bias, kSpeedBiasSize, nullptr}},
        sigmas);
  }

  void reset() {
    window.clear();
    status = VioStatus::kInitializing;
    frames_without_vision = 0;
  }

  FrameEstimate initialise(const FrameObservations& frame);
  bool featuresStill(const FrameObservations& frame) const;
  static int stereoMatched(const FrameObservations& frame);
  bool initialiseInMotion();
  FrameEstimate track(const FrameObservations& frame);
  std::string healthProblem(const ceres::Solver::Summary& summary,
                            const std::vector<Factor>& factors, FrameEstimate* out);
  FrameEstimate output(double t_s) const;
  void trimImu();
};

FrameEstimate VioEstimator::Impl::output(double t_s) const {
  FrameEstimate e;
  e.t_s = t_s;
  e.status = status;
  if (status == VioStatus::kTracking) {
    const Keyframe& k = window.keyframes.back();
    e.T_W_B = k.T_W_B();
    e.T_W_C = e.T_W_B * rig.T_B_Cl;
    e.v_W_B = k.velocity();
    e.bias = k.bias();
  }
  return e;
}

FrameEstimate VioEstimator::Impl::initialise(const FrameObservations& frame) {
  std::optional<InitialState> still = initializeFromStandstill(imu, frame.t_s, config.standstill);
  if (still && !featuresStill(frame)) still.reset();
  if (still) {
    window.clear();
    Keyframe& k = pushKeyframe(frame.t_s);
    k.setPose(still->R_W_B, still->p_W_B);
    for (int i = 0; i < 3; ++i) k.speed_bias[3 + i] = still->bias.gyro_rad_s[i];
    setFirstPrior(config.prior_roll_pitch_rad, config.prior_velocity_mps);
    window.addObservations(k.id, frame.features);
    window.triangulate(config.min_depth_m, config.max_depth_m);
    status = VioStatus::kTracking;
    FrameEstimate e = output(frame.t_s);
    e.reason = "initialised at standstill";
    return e;
  }
  // In motion: keyframes with visual-only stereo poses (rotation predicted by the gyro), aligned
  // with the IMU once there are init_frames of them.
  if (!rig.right) {
    FrameEstimate e = output(frame.t_s);
    e.reason = "waiting for standstill (monocular rig: no in-motion initialisation)";
    return e;
  }
  // Only in motion: until the IMU shows motion, standstill initialisation is the better one.
  if (classifyMotion(imu, frame.t_s, config.standstill) != ImuMotion::kMoving) {
    window.clear();
    FrameEstimate e = output(frame.t_s);
    e.reason = "waiting for standstill (or motion) over standstill.window_s of IMU samples";
    return e;
  }
  if (!window.keyframes.empty() && imu.front().t_s > window.keyframes.back().t_s) window.clear();
  if (window.keyframes.empty() && imu.front().t_s > frame.t_s - 1e-9) {
    FrameEstimate e = output(frame.t_s);
    e.reason = "waiting for IMU samples before the first frame";
    return e;
  }
  // Visual-only poses need vision: a frame with too few stereo-matched features (a blind or
  // textureless stretch) restarts the set of initialisation keyframes instead of joining it
  // with a pose that is the gyro's guess and a position that never moved.
  if (stereoMatched(frame) < config.min_observations) {
    window.clear();
    FrameEstimate e = output(frame.t_s);
    e.reason = "waiting for stereo features to start in motion";
    return e;
  }
  const bool first = window.keyframes.empty();
  Keyframe& k = pushKeyframe(frame.t_s);
  if (!first) {
    const Keyframe& prev = window.keyframes[window.keyframes.size() - 2];
    const Eigen::Isometry3d T_prev = prev.T_W_B();
    k.setPose(T_prev.linear() * k.from_previous->deltaR(), T_prev.translation());
  }
  for (int i = 0; i < 3; ++i) k.speed_bias[i] = 0.0;
  window.addObservations(k.id, frame.features);
  window.triangulate(config.min_depth_m, config.max_depth_m);
  if (!first) {
    const internal::SolveSettings visual = settings(true);
    const std::vector<Factor> factors = window.buildFactors(visual);
    window.solve(factors, visual);
    window.removeOutliers(factors, config.outlier_px);
  }
  while (static_cast<int>(window.keyframes.size()) > config.init_frames) {
    const std::int64_t oldest = window.keyframes.front().id;
    for (auto it = window.landmarks.begin(); it != window.landmarks.end();) {
      it = it->second.anchor_id == oldest ? window.landmarks.erase(it) : std::next(it);
    }
    window.keyframes.pop_front();
    window.keyframes.front().from_previous.reset();
  }
  if (static_cast<int>(window.keyframes.size()) == config.init_frames && initialiseInMotion()) {
    status = VioStatus::kTracking;
    FrameEstimate e = output(frame.t_s);
    e.reason = "initialised in motion";
    return e;
  }
  FrameEstimate e = output(frame.t_s);
  e.reason = "waiting for standstill or stereo motion";
  return e;
}

bool VioEstimator::Impl::initialiseInMotion() {
  std::vector<Eigen::Isometry3d> T_V_B;
  std::vector<Preintegration> pre;
  for (const Keyframe& k : window.keyframes) {
    T_V_B.push_back(k.T_W_B());
    if (k.from_previous) pre.push_back(*k.from_previous);
  }
  const std::optional<AlignmentResult> a = alignVisualInertial(T_V_B, &pre, config.gravity_mps2);
  if (!a) return false;
  // Rotate the window into W; anchored inverse depths do not change with the world frame.
  for (std::size_t i = 0; i < window.keyframes.size(); ++i) {
    Keyframe& k = window.keyframes[i];
    k.setPose(a->R_W_V * T_V_B[i].linear(), a->R_W_V * T_V_B[i].translation());
    const Eigen::Vector3d v_W = a->R_W_V * a->v_V_B[i];
    for (int j = 0; j < 3; ++j) {
      k.speed_bias[j] = v_W[j];
      k.speed_bias[3 + j] = a->gyro_bias[j];
      k.speed_bias[6 + j] = 0.0;
    }
    if (k.from_previous) *k.from_previous = pre[i - 1];
  }
  // A looser prior than at standstill: gravity and velocity come from a short, noisy window.
  setFirstPrior(5.0 * config.prior_roll_pitch_rad, 5.0 * config.prior_velocity_mps);
  const internal::SolveSettings full = settings(false);
  const std::vector<Factor> factors = window.buildFactors(full);
  const ceres::Solver::Summary summary = window.solve(factors, full);
  if (!summary.IsSolutionUsable()) {
    window.clear();
    return false;
  }
  return true;
}

FrameEstimate VioEstimator::Impl::track(const FrameObservations& frame) {
  Keyframe& k = pushKeyframe(frame.t_s);
  window.addObservations(k.id, frame.features);
  window.triangulate(config.min_depth_m, config.max_depth_m);
  const internal::SolveSettings s = settings(false);
  std::vector<Factor> factors = window.buildFactors(s);
  const ceres::Solver::Summary summary = window.solve(factors, s);
  FrameEstimate e;
  const std::string problem = healthProblem(summary, factors, &e);
  if (!problem.empty()) {
    reset();
    FrameEstimate failed = output(frame.t_s);
    failed.status = VioStatus::kFailed;
    failed.reason = problem;
    return failed;
  }
  window.removeOutliers(factors, config.outlier_px);
  // Re-integrate where the bias moved far from its linearisation point.
  for (Keyframe& kf : window.keyframes) {
    if (!kf.from_previous) continue;
    const Keyframe& prev = window.keyframe(kf.id - 1);
    const ImuBias now = prev.bias(), used = kf.from_previous->bias();
    if ((now.gyro_rad_s - used.gyro_rad_s).norm() > config.reintegrate_gyro_bias_rad_s ||
        (now.accel_mps2 - used.accel_mps2).norm() > config.reintegrate_accel_bias_mps2) {
      auto again = std::make_shared<Preintegration>(*kf.from_previous);
      again->reintegrate(now);
      kf.from_previous = again;
    }
  }
  if (static_cast<int>(window.keyframes.size()) > config.window_size) {
    factors = window.buildFactors(s);  // outliers gone, fresh IMU factors
    window.marginaliseOldest(factors);
  }
  FrameEstimate out = output(frame.t_s);
  out.landmarks = e.landmarks;
  out.observations_newest = e.observations_newest;
  out.solver_iterations = static_cast<int>(summary.iterations.size());
  return out;
}

std::string VioEstimator::Impl::healthProblem(const ceres::Solver::Summary& summary,
                                              const std::vector<Factor>& factors,
                                              FrameEstimate* out) {
  if (!summary.IsSolutionUsable()) return "solver failed: " + summary.message;
  const Keyframe& newest = window.keyframes.back();
  for (const Keyframe& k : window.keyframes) {
    for (double x : k.pose) {
      if (!std::isfinite(x)) return "non-finite pose";
    }
    for (double x : k.speed_bias) {
      if (!std::isfinite(x)) return "non-finite velocity or bias";
    }
  }
  const ImuBias b = newest.bias();
  if (newest.velocity().norm() > config.max_speed_mps) {
    return "speed " + std::to_string(newest.velocity().norm()) + " m/s above max_speed_mps";
  }
  if (b.gyro_rad_s.norm() > config.max_gyro_bias_rad_s) {
    return "gyro bias " + std::to_string(b.gyro_rad_s.norm()) + " rad/s above max_gyro_bias_rad_s";
  }
  if (b.accel_mps2.norm() > config.max_accel_bias_mps2) {
    return "accel bias " + std::to_string(b.accel_mps2.norm()) + " m/s^2 above max_accel_bias_mps2";
  }
  std::vector<double> errors, errors_newest;
  std::set<std::uint64_t> tracks;
  for (const Factor& f : factors) {
    if (f.kind != FactorKind::kReprojection) continue;
    errors.push_back(internal::Window::reprojectionErrorPx(f));
    tracks.insert(f.track_id);
    if (f.keyframe_id == newest.id) errors_newest.push_back(errors.back());
  }
  out->landmarks = static_cast<int>(tracks.size());
  out->observations_newest = static_cast<int>(errors_newest.size());
  // The whole window, and the newest frame alone (where bad data shows first).
  for (auto* e : {&errors, &errors_newest}) {
    if (static_cast<int>(e->size()) < config.min_observations) continue;
    std::nth_element(e->begin(), e->begin() + e->size() / 2, e->end());
    const double median = (*e)[e->size() / 2];
    if (median > config.max_median_reprojection_px) {
      return std::string("median reprojection error ") + std::to_string(median) + " px " +
             (e == &errors ? "in the window" : "in the newest frame") +
             " above max_median_reprojection_px";
    }
  }
  // At rest the IMU alone holds the pose (and a monocular rig triangulates nothing).
  const bool at_rest = classifyMotion(imu, newest.t_s, config.standstill) == ImuMotion::kStill;
  frames_without_vision = out->observations_newest < config.min_observations && !at_rest
                              ? frames_without_vision + 1
                              : 0;
  if (frames_without_vision > config.max_frames_without_vision) {
    return "fewer than min_observations tracked for more than max_frames_without_vision frames";
  }
  return "";
}

int VioEstimator::Impl::stereoMatched(const FrameObservations& frame) {
  int matched = 0;
  for (const FeatureObservation& o : frame.features) matched += o.xy_right_norm.has_value() ? 1 : 0;
  return matched;
}

bool VioEstimator::Impl::featuresStill(const FrameObservations& frame) const {
  // The oldest kept frame, about window_s ago, against this one.
  if (recent_frames.empty() ||
      recent_frames.front().t_s > frame.t_s - 0.9 * config.standstill.window_s) {
    return false;
  }
  std::unordered_map<std::uint64_t, Eigen::Vector2d> before;
  for (const FeatureObservation& o : recent_frames.front().features) {
    before[o.track_id] = rig.left.toPixel(o.xy_left_norm);
  }
  std::vector<double> motion_px;
  for (const FeatureObservation& o : frame.features) {
    const auto it = before.find(o.track_id);
    if (it != before.end()) {
      motion_px.push_back((rig.left.toPixel(o.xy_left_norm) - it->second).norm());
    }
  }
  // Too few common tracks to tell: no standstill. The IMU alone cannot tell rest from smooth
  // motion at constant velocity (a blind stretch in motion passed its test and started the
  // window at zero velocity), and without tracks there is nothing to start from anyway.
  if (static_cast<int>(motion_px.size()) < config.min_observations) return false;
  std::nth_element(motion_px.begin(), motion_px.begin() + motion_px.size() / 2, motion_px.end());
  return motion_px[motion_px.size() / 2] < config.standstill.max_feature_motion_px;
}

void VioEstimator::Impl::trimImu() {
  if (window.keyframes.empty()) {
    const double keep_from = imu.empty() ? 0.0 : imu.back().t_s - 2.0 * config.standstill.window_s;
    imu.erase(imu.begin(), std::find_if(imu.begin(), imu.end(), [&](const ImuMeasurement& m) {
                return m.t_s >= keep_from;
              }));
    return;
  }
  const double t0 = window.keyframes.back().t_s;
  auto first_needed =
      std::find_if(imu.begin(), imu.end(), [&](const ImuMeasurement& m) { return m.t_s > t0; });
  if (first_needed != imu.begin()) --first_needed;
  // Keep a standstill window too, for re-initialisation.
  while (first_needed != imu.begin() && first_needed->t_s > t0 - 2.0 * config.standstill.window_s) {
    --first_needed;
  }
  imu.erase(imu.begin(), first_needed);
}

VioEstimator::VioEstimator(const VioConfig& config, const CameraRig& rig) {
  config.validate();
  rig.validate();
  impl_ = std::make_unique<Impl>(config, rig);
}

VioEstimator::~VioEstimator() = default;

VioStatus VioEstimator::status() const { return impl_->status; }

void VioEstimator::addImu(const ImuMeasurement& sample) {
  if (!impl_->imu.empty() && !(sample.t_s > impl_->imu.back().t_s)) {
    throw InputError("VioEstimator::addImu: sample at t=" + std::to_string(sample.t_s) +
                     " s is not after the previous one");
  }
  impl_->imu.push_back(sample);
}

FrameEstimate VioEstimator::addFrame(const FrameObservations& frame) {
  Impl& m = *impl_;
  if (!(frame.t_s > m.last_frame_t_s)) {
    throw InputError("VioEstimator::addFrame: frame at t=" + std::to_string(frame.t_s) +
                     " s is not after the previous one");
  }
  if (m.imu.empty() || m.imu.back().t_s < frame.t_s - 1e-9) {
    throw InputError("VioEstimator::addFrame: IMU samples end before the frame at t=" +
                     std::to_string(frame.t_s) + " s");
  }
  m.last_frame_t_s = frame.t_s;
  FrameEstimate e = m.status == VioStatus::kTracking ? m.track(frame) : m.initialise(frame);
  m.recent_frames.push_back(frame);
  while (m.recent_frames.size() > 1 &&
         m.recent_frames[1].t_s <= frame.t_s - m.config.standstill.window_s + 1e-9) {
    m.recent_frames.pop_front();
  }
  m.trimImu();
  return e;
}

}  // namespace strata::odometry

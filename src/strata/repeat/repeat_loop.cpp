#include "strata/repeat/repeat_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "strata/core/error.h"
#include "strata/repeat/internal/repeat_run.h"

namespace strata::repeat {
namespace {

using Clock = std::chrono::steady_clock;

std::int64_t ticksOf(double period_s, double step_s) {
  return std::max<std::int64_t>(1, std::llround(period_s / step_s));
}

MapperConfig liveMapConfig(const RepeatConfig& c) {
  MapperConfig m;
  m.map.voxel_size_m = c.voxel_size_m;
  m.map.min_depth_m = static_cast<float>(c.camera.min_range_m);
  m.map.max_depth_m = static_cast<float>(c.camera.max_range_m);
  m.map.allocate_free_space = true;
  m.esdf = true;
  // A surface counts once several frames saw it: single noisy measurements (flying pixels at
  // a pillar's silhouette) made phantom blocks of the path ahead in the office. Every frame
  // weighs 1, so that the count is of frames (at 1/z^2 a crate 2 m ahead needed 3 s of frames).
  m.map.weight_mode = WeightMode::kConstant;
  m.esdf_config.min_weight = c.esdf_min_weight;
  m.change_detection = false;
  return m;
}

}  // namespace

localize::FusionConfig RepeatConfig::defaultFusion() {
  localize::FusionConfig f;
  // The simulated VIO's drift (TeachConfig::defaultDrift): 2.5 cm/sqrt(m), 0.01 rad/sqrt(m).
  f.translation_variance_per_m = 0.025 * 0.025;
  f.rotation_variance_per_m = 0.01 * 0.01;
  return f;
}

void RepeatConfig::validate() const {
  robot.validate();
  camera.validate();
  drift.validate();
  follower.validate();
  localizer.validate();
  fusion.validate();
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  if (!positive(camera_rate_hz) || !positive(motion_step_s) || !positive(esdf_period_s) ||
      !positive(stuck_after_s)) {
    throw InputError("repeat rates, steps and periods must be > 0");
  }
  if (localize_every < 0) throw InputError("localize_every must be >= 0");
  if (!(voxel_size_m > 0.0f)) throw InputError("repeat voxel size must be > 0");
  if (!(change_margin_m >= 0.0f)) throw InputError("repeat change_margin_m must be >= 0");
  if (!(teach_window_m >= 0.0)) throw InputError("repeat teach_window_m must be >= 0");
  if (!(check_ahead_m > 0.0f) || !(check_radius_m > 0.0f)) {
    throw InputError("repeat check_ahead_m and check_radius_m must be > 0");
  }
  if (!(time_limit_s >= 0.0)) throw InputError("repeat time limit must be >= 0");
}

Eigen::Isometry3d robotCamera(const Eigen::Vector3f& p_W, float yaw_rad) {
  return explore::cameraPose({p_W, yaw_rad}, 0.0f);
}

float yawOf(const Eigen::Isometry3d& T_W_C) {
  const Eigen::Vector3d forward = T_W_C.linear().col(2);
  return static_cast<float>(std::atan2(forward.y(), forward.x()));
}

RepeatRun::RepeatRun(const sim::World& world, int session, const TaughtPath& taught,
                     const localize::PriorMap* map, const RepeatConfig& config,
                     vk::Context& context)
    : world_(world),
      taught_(taught),
      map_(map),
      config_(config),
      context_(context),
      scene_(world.buildScene(session)),
      camera_(config.camera.config()),
      lighting_(sessionLighting(world, session)),
      fusion_(config.fusion),
      drift_(config.drift, config.seed * 7919u + 29u),
      follower_(taught, config.follower, config.robot) {
  config_.validate();
  if (config_.localize_every > 0) {
    if (map_ == nullptr) throw InputError("a repeat with localisation needs the teach map");
    localizing_ = true;
  }
  if (map_ != nullptr) {
    for (const localize::MapKeyframe& k : map_->keyframes()) {
      // The taught frame nearest in time: its arc length along the taught path.
      const auto it = std::lower_bound(taught.timestamp_s.begin(), taught.timestamp_s.end(),
                                       k.timestamp_s - 1e-6);
      std::size_t i = static_cast<std::size_t>(it - taught.timestamp_s.begin());
      if (i >= taught.timestamp_s.size()) i = taught.timestamp_s.size() - 1;
      if (i > 0 &&
          k.timestamp_s - taught.timestamp_s[i - 1] < taught.timestamp_s[i] - k.timestamp_s) {
        --i;
      }
      keyframe_s_.push_back(taught.s_m[i]);
    }
  }
  if (config_.live_map) {
    mapper_ = std::make_unique<Mapper>(liveMapConfig(config_), context_);
  }
  // The teach started at its first true pose; so does the repeat.
  p_W_ = taught.p_W.front();
  yaw_W_ = taught.yaw_rad.front();
  T_O_C_ = drift_.next(robotCamera(p_W_, yaw_W_));
  updateEstimate(fusion_.predict(0.0, T_O_C_));
  result_.localization = config_.localize_every > 0;
  result_.taught_length_m = taught.length_m();
}

RepeatResult RepeatRun::run(const RepeatProgress& progress) {
  const Clock::time_point wall_start = Clock::now();
  const double dt = config_.motion_step_s;
  const std::int64_t frame_ticks = ticksOf(1.0 / config_.camera_rate_hz, dt);
  const std::int64_t esdf_ticks = ticksOf(config_.esdf_period_s, dt);
  const std::int64_t progress_ticks = ticksOf(5.0, dt);
  const double limit_s = config_.time_limit_s > 0.0
                             ? config_.time_limit_s
                             : 3.0 * taught_.length_m() / config_.robot.max_speed_mps + 60.0;
  double best_progress_m = -1.0, progress_at_s = 0.0;
  std::uint64_t frames = 0;
  record(0.0);
  for (std::int64_t tick = 0;; ++tick) {
    const double t = static_cast<double>(tick) * dt;
    if (tick % frame_ticks == 0) frame(t, frames++);
    if (config_.live_map && tick % esdf_ticks == 0 && tick > 0 && !checkAhead(t)) break;
    const FollowerCommand command =
        follower_.command(T_M_C_.translation().cast<float>(), yawOf(T_M_C_), t);
    if (command.done) {
      result_.finished = true;
      result_.stop_reason = "end of the taught path";
      break;
    }
    if (follower_.progress_m() > best_progress_m + 0.05) {
      best_progress_m = follower_.progress_m();
      progress_at_s = t;
    }
    if (t - progress_at_s > config_.stuck_after_s) {
      result_.stop_reason = "no progress along the taught path for " +
                            std::to_string(static_cast<int>(config_.stuck_after_s)) + " s";
      break;
    }
    if (t >= limit_s) {
      result_.stop_reason = "time limit";
      break;
    }
    move(command, t);
    record(t + dt);
    if (progress && tick % progress_ticks == 0) {
      progress(t, follower_.progress_m(), taught_.length_m(), result_);
    }
  }
  result_.progress_m = follower_.progress_m();
  result_.odometry_drift_final_m = (T_O_C_.translation().cast<float>() - p_W_).norm();
  result_.wall_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  scoreRepeat(result_, taught_);
  if (mapper_ && !config_.save_map_path.empty()) mapper_->save(config_.save_map_path);
  return std::move(result_);
}

RepeatResult runRepeat(const sim::World& world, int session, const TaughtPath& taught,
                       const localize::PriorMap* map, const RepeatConfig& config,
                       vk::Context& context, const RepeatProgress& progress) {
  world.session(session);  // InputError for a session the world lacks
  RepeatRun run(world, session, taught, map, config, context);
  return run.run(progress);
}

}  // namespace strata::repeat

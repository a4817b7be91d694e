// The steps of a repeat run (internal/repeat_run.h): a camera frame, a localisation, one motion
// step of the robot, the check of the path ahead and a detour.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "strata/plan/grid_astar.h"
#include "strata/repeat/internal/repeat_run.h"

namespace strata::repeat {
namespace {

std::string pointText(const Eigen::Vector3f& p) {
  char text[64];
  std::snprintf(text, sizeof(text), "(%.2f, %.2f, %.2f)", p.x(), p.y(), p.z());
  return text;
}

/// Most detours in one run before it stops (a blocked stretch the live map keeps finding).
constexpr std::size_t kMaxDetours = 10;

}  // namespace

void RepeatRun::frame(double t_s, std::uint64_t index) {
  sim::SimulatedFrame rendered = camera_.render(*scene_, robotCamera(p_W_, yaw_W_), lighting_,
                                                config_.seed * 1000003u + index);
  RgbdFrame rgbd =
      sim::makeRgbdFrame(std::move(rendered), T_M_C_, t_s, "repeat-" + std::to_string(index));
  if (localizing_ && index % static_cast<std::uint64_t>(config_.localize_every) == 0) {
    localize(rgbd, t_s);
  }
  rgbd.T_W_C = T_M_C_;  // fused at the estimate, corrected by this frame's localisation
  if (mapper_) mapper_->integrate(rgbd, camera_.config().intrinsics);
}

const localize::Localizer& RepeatRun::localWindow() {
  const double progress = follower_.progress_m();
  if (config_.window_behind_m <= 0.0 && config_.window_ahead_m <= 0.0) {
    if (!window_localizer_) {
      window_localizer_ = std::make_unique<localize::Localizer>(*map_, config_.localizer);
    }
    return *window_localizer_;
  }
  if (window_localizer_ && std::abs(progress - window_centre_m_) < config_.window_step_m) {
    return *window_localizer_;
  }
  std::vector<localize::MapKeyframe> near;
  for (std::size_t k = 0; k < keyframe_s_.size(); ++k) {
    if (keyframe_s_[k] >= progress - config_.window_behind_m &&
        keyframe_s_[k] <= progress + config_.window_ahead_m) {
      near.push_back(map_->keyframes()[k]);
    }
  }
  window_localizer_.reset();
  window_map_.reset();
  if (near.size() >= 2) {
    window_map_ = std::make_unique<localize::PriorMap>(std::move(near), map_->config());
  }
  window_localizer_ =
      std::make_unique<localize::Localizer>(window_map_ ? *window_map_ : *map_, config_.localizer);
  window_centre_m_ = progress;
  return *window_localizer_;
}

void RepeatRun::localize(const RgbdFrame& frame, double t_s) {
  std::optional<localize::PosePrior> prior = fusion_.prior();
  if (!prior) prior = localize::PosePrior{T_M_C_};
  const localize::Localization l =
      localWindow().localize(frame.color, frame.depth, camera_.config().intrinsics, prior);
  const localize::FusedPose fused = fusion_.correct(l);
  LocalizationRecord r;
  r.t_s = t_s;
  r.localized = l.localized;
  r.accepted = fused.status == localize::FusionStatus::kCorrected;
  r.note = !l.localized ? l.reason : (r.accepted ? "" : fused.note);
  r.time_ms = l.time_ms;
  result_.localizations.push_back(r);
  updateEstimate(fused);
}

void RepeatRun::updateEstimate(const localize::FusedPose& fused) {
  if (localizing_ && fused.status != localize::FusionStatus::kUninitialised) {
    T_M_C_ = fused.T_W_C;
  } else {
    T_M_C_ = T_O_C_;  // T_M_O = identity: the repeat starts where the teach did
  }
}

void RepeatRun::move(const FollowerCommand& command, double t_s) {
  const double dt = config_.motion_step_s;
  const explore::RobotConfig& robot = config_.robot;
  Eigen::Vector3f dv = command.v_M - v_M_;
  const float max_dv = static_cast<float>(robot.max_accel_mps2 * dt);
  if (dv.norm() > max_dv) dv *= max_dv / dv.norm();
  v_M_ += dv;
  if (v_M_.norm() > robot.max_speed_mps) v_M_ *= robot.max_speed_mps / v_M_.norm();
  const float rate =
      std::clamp(command.yaw_rate_radps, -robot.max_yaw_rate_radps, robot.max_yaw_rate_radps);
  // The command is in the estimate's axes; the robot executes it in its own body frame, so the
  // true motion is turned by the estimate's yaw error.
  const float yaw_error = yaw_W_ - yawOf(T_M_C_);
  const Eigen::Matrix3f R =
      Eigen::AngleAxisf(yaw_error, Eigen::Vector3f::UnitZ()).toRotationMatrix();
  p_W_ += R * v_M_ * static_cast<float>(dt);
  yaw_W_ = explore::wrapAngle(yaw_W_ + rate * static_cast<float>(dt));
  T_O_C_ = drift_.next(robotCamera(p_W_, yaw_W_));
  if (localizing_) {
    updateEstimate(fusion_.predict(t_s + dt, T_O_C_));
  } else {
    T_M_C_ = T_O_C_;
  }
}

Mapper& RepeatRun::teachWindow() {
  const double progress = follower_.progress_m();
  const bool whole = config_.teach_window_m <= 0.0;
  if (teach_map_ && (whole || std::abs(progress - teach_centre_m_) < config_.window_step_m)) {
    return *teach_map_;
  }
  MapperConfig mapper_config = mapper_->config();
  teach_map_ = std::make_unique<Mapper>(mapper_config, context_);
  for (std::size_t k = 0; k < keyframe_s_.size(); ++k) {
    if (!whole && (keyframe_s_[k] < progress - config_.teach_window_m ||
                   keyframe_s_[k] > progress + 2.0 * config_.teach_window_m)) {
      continue;
    }
    const localize::MapKeyframe& keyframe = map_->keyframes()[k];
    RgbdFrame frame;
    frame.depth = keyframe.depth;
    frame.T_W_C = keyframe.T_W_C;
    frame.timestamp_s = keyframe.timestamp_s;
    frame.name = "teach keyframe " + std::to_string(keyframe.store_id);
    teach_map_->integrate(frame, keyframe.intrinsics);
  }
  teach_map_->updateEsdf();
  teach_centre_m_ = progress;
  return *teach_map_;
}

bool RepeatRun::checkAhead(double t_s) {
  mapper_->updateEsdf();
  if (!checker_) {
    checker_ = std::make_unique<plan::DeviceCollisionChecker>(context_, *mapper_->deviceEsdf());
  }
  checker_->setEsdf(*mapper_->deviceEsdf());
  const std::vector<Eigen::Vector3f> ahead = follower_.ahead(config_.check_ahead_m);
  if (ahead.size() < 2) return true;
  const float radius = config_.check_radius_m;
  const std::vector<EsdfSample> live = mapper_->distances(ahead);
  std::vector<EsdfSample> before;
  if (map_ != nullptr) before = teachWindow().distances(ahead);
  std::optional<std::size_t> first_blocked;
  for (std::size_t i = 0; i < ahead.size() && !first_blocked; ++i) {
    if (live[i].status != EsdfStatus::kKnown || !(live[i].distance_m < radius)) continue;
    // With the teach map: a surface change_margin_m nearer than the teach map knew it (where
    // the teach map does not know the place, the drifted map frame may put a wall the teach
    // never saw across the taught path: no block). Without it: any surface.
    const bool new_surface =
        before.empty() || (before[i].status == EsdfStatus::kKnown &&
                           before[i].distance_m > live[i].distance_m + config_.change_margin_m);
    if (new_surface) first_blocked = i;
  }
  if (!first_blocked) {
    pending_block_.reset();
    return true;
  }
  const Eigen::Vector3f blocked = ahead[*first_blocked];
  // A block counts once two checks in a row see it (about) there: a phantom surface from a few
  // noisy frames is carved away by the frames that look through it as the robot approaches.
  if (!pending_block_ || (*pending_block_ - blocked).norm() > config_.block_confirm_m) {
    pending_block_ = blocked;
    return true;
  }
  pending_block_.reset();
  float blocked_at_m = 0.0f;
  for (std::size_t i = 1; i <= *first_blocked; ++i)
    blocked_at_m += (ahead[i] - ahead[i - 1]).norm();
  v_M_.setZero();  // brakes (the check looks further ahead than the braking distance)
  result_.stops.push_back(
      {t_s, p_W_, "path ahead blocked in the live map at " + pointText(blocked), false});
  return planDetour(t_s, blocked, follower_.progress_m() + blocked_at_m);
}

bool RepeatRun::planDetour(double /*t_s*/, const Eigen::Vector3f& blocked_M, double blocked_s) {
  if (result_.detours >= kMaxDetours) {
    result_.stop_reason = "blocked at " + pointText(blocked_M) + ": " +
                          std::to_string(kMaxDetours) + " detours already flown";
    return false;
  }
  std::string why;
  // The robot's radius first; then three quarters of it, as doors the teach flew through leave
  // the live map's voxels (ESDF to voxel centres, depth noise) less room than the truth.
  for (const float radius : {config_.robot.radius_m, 0.75f * config_.robot.radius_m}) {
    // The goal: the first taught point past the block whose sphere is free in the live map.
    std::optional<double> goal_s;
    for (double s = blocked_s + 0.5; s <= blocked_s + 6.0 && s <= taught_.length_m(); s += 0.25) {
      if (checker_->spheresFree({taught_.at(s)}, radius, UnknownPolicy::kOccupied)[0]) {
        goal_s = s;
        break;
      }
    }
    if (!goal_s) {
      why = "no free taught point within 6 m past the block";
      continue;
    }
    plan::GridAStarPlanner planner(mapper_->esdf(), *checker_);
    plan::PlanRequest request;
    request.start_W = T_M_C_.translation().cast<float>();
    request.goal_W = taught_.at(*goal_s);
    request.radius_m = radius;
    request.unknown = UnknownPolicy::kOccupied;  // through space seen free only
    const plan::PlanResult plan = planner.plan(request);
    if (!plan.success) {
      why = "no detour on the live map (" + plan.message + ")";
      continue;
    }
    follower_.setDetour(plan.path_W, *goal_s);
    ++result_.detours;
    result_.stops.back().resumed = true;
    return true;
  }
  result_.stop_reason = "blocked at " + pointText(blocked_M) + ": " + why;
  return false;
}

void RepeatRun::record(double t_s) {
  const Eigen::Vector3f estimate = T_M_C_.translation().cast<float>();
  if (!result_.true_W.empty()) result_.path_length_m += (p_W_ - result_.true_W.back()).norm();
  result_.t_s.push_back(t_s);
  result_.sim_time_s = t_s;
  result_.true_W.push_back(p_W_);
  result_.estimate_M.push_back(estimate);
  const float clearance = scene_->signedDistance(p_W_);
  if (result_.t_s.size() == 1 || clearance < result_.min_clearance_m) {
    result_.min_clearance_m = clearance;
  }
  const bool inside = clearance < config_.robot.radius_m;
  if (inside) {
    if (!in_collision_) result_.collisions.push_back({t_s, p_W_, clearance});
    if (clearance < result_.collisions.back().clearance_m) {
      result_.collisions.back() = {t_s, p_W_, clearance};
    }
  }
  in_collision_ = inside;
}

}  // namespace strata::repeat

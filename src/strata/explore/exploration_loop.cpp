#include "strata/core/clock.h"
#include "strata/explore/exploration_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "strata/core/error.h"
#include "strata/explore/internal/loop_impl.h"
#include "strata/sim/sensors/rgbd_camera.h"

namespace strata::explore {
namespace {

using Clock = std::chrono::steady_clock;

std::int64_t ticksOf(double period_s, double step_s) {
  return std::max<std::int64_t>(1, std::llround(period_s / step_s));
}

/// Contiguous stretches of samples closer to a surface than the radius, each with its closest
/// sample; the smallest clearance of all samples.
std::vector<CollisionEvent> findCollisions(const ExplorationTruth& truth,
                                           const std::vector<Eigen::Vector3f>& flown_W,
                                           const std::vector<double>& flown_time_s, float radius_m,
                                           float& min_clearance_m) {
  std::vector<CollisionEvent> events;
  bool inside = false;
  min_clearance_m = std::numeric_limits<float>::infinity();
  for (std::size_t i = 0; i < flown_W.size(); ++i) {
    const float d = truth.minClearance({flown_W[i]});
    min_clearance_m = std::min(min_clearance_m, d);
    if (d < radius_m) {
      if (!inside) events.push_back({flown_time_s[i], flown_W[i], d});
      if (d < events.back().clearance_m) events.back() = {flown_time_s[i], flown_W[i], d};
    }
    inside = d < radius_m;
  }
  return events;
}

/// The robot's position and the rest of its path, cut after length_m along it.
std::vector<Eigen::Vector3f> pathAhead(const PathFollower& follower, float length_m) {
  std::vector<Eigen::Vector3f> ahead_W{follower.pose().position_W};
  float left_m = length_m;
  for (const Waypoint& w : follower.remaining()) {
    const Eigen::Vector3f step = w.position_W - ahead_W.back();
    const float step_m = step.norm();
    if (step_m >= left_m) {
      ahead_W.push_back(ahead_W.back() + step * (left_m / step_m));
      break;
    }
    ahead_W.push_back(w.position_W);
    left_m -= step_m;
  }
  return ahead_W;
}

}  // namespace

plan::CollisionChecker& ExplorationLoop::refreshChecker() {
  mapper_->updateEsdf();
  if (!impl_->checker) {
    impl_->checker =
        std::make_unique<plan::DeviceCollisionChecker>(context_, *mapper_->deviceEsdf());
  }
  impl_->checker->setEsdf(*mapper_->deviceEsdf());
  if (!config_.surface_hits) return *impl_->checker;
  if (!impl_->guarded) {
    impl_->guarded = std::make_unique<HitGuardedChecker>(*impl_->checker, impl_->hits);
  }
  return *impl_->guarded;
}

bool ExplorationLoop::pathAheadBlocked() {
  // The ESDF as of the last planning step (it passed the path then, through space already seen
  // free); the hits as of this frame. Refreshing the ESDF here too cost 15-25 ms a frame.
  plan::CollisionChecker& checker = config_.surface_hits
                                        ? static_cast<plan::CollisionChecker&>(*impl_->guarded)
                                        : *impl_->checker;
  const PathFollower& follower = impl_->follower;
  const Eigen::Vector3f& here_W = follower.pose().position_W;
  // Half the planners' margin: brake for what the path would truly come near, not for every
  // voxel the plan's margin no longer clears (braking there stopped the robot by door frames
  // where the planners could not go on: office seed 4 at 76.7 % instead of 99 %).
  float radius_m = config_.robot.radius_m + 0.5f * (config_.checkRadius() - config_.robot.radius_m);
  if (!checker.spheresFree({here_W}, radius_m, UnknownPolicy::kOccupied)[0]) {
    radius_m = config_.robot.radius_m;
    // Already touching something the map did not hold: the path decides, not this check.
    if (!checker.spheresFree({here_W}, radius_m, UnknownPolicy::kOccupied)[0]) return false;
  }
  return !checker.pathFree(pathAhead(follower, config_.inflight_lookahead_m), radius_m,
                           UnknownPolicy::kOccupied);
}

void ExplorationLoop::fuseFrame(double sim_time_s, std::uint64_t index) {
  const Eigen::Isometry3d T_W_C =
      cameraPose(impl_->follower.pose(), framePitch(config_, index));
  sim::SimulatedFrame frame =
      impl_->camera.render(truth_.scene(), T_W_C, impl_->lighting, config_.seed * 1000003u + index);
  const RgbdFrame rgbd =
      sim::makeRgbdFrame(std::move(frame), T_W_C, sim_time_s, "explore-" + std::to_string(index));
  mapper_->integrate(rgbd, impl_->camera.config().intrinsics);
  if (config_.surface_hits) {
    impl_->hits.addFrame(rgbd.depth, impl_->camera.config().intrinsics, rgbd.T_W_C);
  }
}

ExplorationResult ExplorationLoop::run(ExplorationPlanner& planner,
                                       const ExplorationProgress& progress) {
  const Clock::time_point wall_start = Clock::now();
  ExplorationResult result;
  result.planner = planner.name();
  result.reachable_voxels = truth_.reachableVoxels();
  result.start_clearing_fraction =
      truth_.exploredFraction(mapper_->download(), config_.gain.min_weight);

  const double dt = config_.motion_step_s;
  const std::int64_t frame_ticks = ticksOf(1.0 / config_.camera_rate_hz, dt);
  const std::int64_t eval_ticks = ticksOf(config_.eval_period_s, dt);
  const std::int64_t limit_ticks = ticksOf(config_.time_limit_s, dt);
  PathFollower& follower = impl_->follower;
  double last_plan_s = -1e9;
  int idle_steps = 0;
  std::size_t steps_at_last_point = 0;
  std::uint64_t frames = 0;
  result.flown_W.push_back(follower.pose().position_W);
  result.flown_time_s.push_back(0.0);

  ExplorationState state;
  state.check_radius_m = config_.checkRadius();
  state.bounds_W = bounds_W_;
  state.gain_config = config_.gain;
  ViewGainKernel& kernel = impl_->gain;
  Mapper& mapper = *mapper_;
  state.gain = [&kernel, &mapper](const std::vector<Eigen::Vector3f>& positions) {
    return kernel.run(mapper.deviceMap(), positions);
  };

  for (std::int64_t tick = 0;; ++tick) {
    const double t = static_cast<double>(tick) * dt;
    if (tick % frame_ticks == 0) {
      fuseFrame(t, frames++);
      if (config_.inflight_checks && follower.moving()) {
        const Clock::time_point check_start = Clock::now();
        ++result.inflight_checks;
        if (pathAheadBlocked()) {
          follower.brake();
          ++result.brakes;
        }
        result.inflight_ms += msSince(check_start);
      }
    }
    if (tick % eval_ticks == 0 || tick >= limit_ticks) {
      CurvePoint point;
      point.sim_time_s = t;
      point.explored_fraction = truth_.exploredFraction(mapper.download(), config_.gain.min_weight);
      point.path_length_m = result.path_length_m;
      double sum_ms = 0.0;
      for (std::size_t i = steps_at_last_point; i < result.steps.size(); ++i) {
        sum_ms += result.steps[i].compute_ms;
      }
      const std::size_t new_steps = result.steps.size() - steps_at_last_point;
      point.compute_ms = new_steps > 0 ? sum_ms / static_cast<double>(new_steps) : 0.0;
      steps_at_last_point = result.steps.size();
      result.curve.push_back(point);
      if (progress) progress(point, result.steps.empty() ? nullptr : &result.steps.back());
      if (point.explored_fraction >= config_.target_fraction) {
        result.stop_reason = "target";
        break;
      }
    }
    if (tick >= limit_ticks) {
      result.stop_reason = "time limit";
      break;
    }
    if (follower.atWaypoint() && (follower.done() || t - last_plan_s >= config_.replan_period_s)) {
      StepRecord record;
      record.sim_time_s = t;
      const Clock::time_point esdf_start = Clock::now();
      state.checker = &refreshChecker();
      record.esdf_ms = msSince(esdf_start);
      state.sim_time_s = t;
      state.pose = follower.pose();
      const Clock::time_point plan_start = Clock::now();
      const ExplorationStep step = planner.plan(state);
      record.compute_ms = msSince(plan_start);
      record.mode = step.mode;
      record.best_gain_m3 = step.best_gain_m3;
      record.tree_nodes = step.tree_nodes;
      record.gain_evaluations = step.gain_evaluations;
      result.steps.push_back(record);
      last_plan_s = t;
      if (step.finished) {
        result.stop_reason = "no gain";
        break;
      }
      idle_steps = step.path.empty() ? idle_steps + 1 : 0;
      if (idle_steps >= config_.max_idle_steps) {
        result.stop_reason = "stuck";
        break;
      }
      if (step.path.empty()) {
        follower.hover(config_.replan_period_s);
      } else {
        follower.setPath(step.path);
      }
    }
    follower.advance(dt);
    const Eigen::Vector3f& p = follower.pose().position_W;
    const float moved = (p - result.flown_W.back()).norm();
    if (moved > 1e-4f) {
      result.path_length_m += moved;
      result.flown_W.push_back(p);
      result.flown_time_s.push_back(t + dt);
    }
    result.sim_time_s = t + dt;
  }
  result.explored_fraction = result.curve.empty() ? 0.0 : result.curve.back().explored_fraction;
  result.collision_events = findCollisions(truth_, result.flown_W, result.flown_time_s,
                                           config_.robot.radius_m, result.min_clearance_m);
  result.hit_obstacles = impl_->hits.obstacleCount();
  result.spheres_refused_by_hits = impl_->guarded ? impl_->guarded->refusedByHits() : 0;
  result.wall_s = msSince(wall_start) / 1000.0;
  return result;
}

}  // namespace strata::explore

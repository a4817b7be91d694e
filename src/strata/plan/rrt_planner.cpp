// RrtPlanner (contract in rrt_planner.h): checks, the OMPL solve (rrt_ompl.cpp), shortening.
#include "strata/core/clock.h"
#include "strata/plan/rrt_planner.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "strata/core/error.h"
#include "strata/plan/internal/rrt_ompl.h"

namespace strata::plan {
namespace {

/// Forwards to a checker and counts the calls (batches; device dispatches on the device).
class CountingChecker final : public CollisionChecker {
 public:
  explicit CountingChecker(CollisionChecker& inner) : inner_(inner) {}
  std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres_W,
                                        float radius_m, UnknownPolicy unknown) override {
    ++batches_;
    spheres_tested_ += centres_W.size();
    return inner_.spheresFree(centres_W, radius_m, unknown);
  }
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points_W) override {
    ++batches_;
    return inner_.sample(points_W);
  }
  float voxelSize() const override { return inner_.voxelSize(); }
  float maxDistance() const override { return inner_.maxDistance(); }
  std::uint64_t batches() const { return batches_; }

 private:
  CollisionChecker& inner_;
  std::uint64_t batches_ = 0;
};

double deviceMs(const CollisionChecker& checker) {
  const auto* device = dynamic_cast<const DeviceCollisionChecker*>(&checker);
  return device != nullptr ? device->deviceMs() : 0.0;
}

void validateRequest(const PlanRequest& request) {
  if (!request.start_W.allFinite() || !request.goal_W.allFinite()) {
    throw InputError("RrtPlanner: start and goal must be finite");
  }
  if (!(request.radius_m >= 0.0f) || !std::isfinite(request.radius_m)) {
    throw InputError("RrtPlanner: radius_m must be finite and >= 0");
  }
  if (!(request.time_budget_s > 0.0) || !std::isfinite(request.time_budget_s)) {
    throw InputError("RrtPlanner: time_budget_s must be finite and > 0");
  }
}

/// Why start or goal cannot be planned from (empty when both are fine): one batch.
std::string endpointProblem(CollisionChecker& checker, const RrtOptions& options,
                            const PlanRequest& request) {
  if (!options.bounds_W.contains(request.start_W)) return "start outside the planning bounds";
  if (!options.bounds_W.contains(request.goal_W)) return "goal outside the planning bounds";
  // As zero-length motions: the radius of the motion checks' samples, so an end that passes can
  // also be left (a plain sphere test of the radius may pass where no motion does).
  const std::vector<std::uint8_t> free =
      checker.segmentsFree({{request.start_W, request.start_W}, {request.goal_W, request.goal_W}},
                           request.radius_m, request.unknown);
  if (free[0] == 0) return "start in collision (or unknown space under kOccupied)";
  if (free[1] == 0) return "goal in collision (or unknown space under kOccupied)";
  return {};
}

}  // namespace

void RrtOptions::validate() const {
  if (bounds_W.isEmpty() || !bounds_W.min().allFinite() || !bounds_W.max().allFinite() ||
      (bounds_W.sizes().array() <= 0.0f).any()) {
    throw InputError("RrtOptions: bounds_W must be finite with a positive extent on every axis");
  }
  if (!(range_m >= 0.0f) || !std::isfinite(range_m)) {
    throw InputError("RrtOptions: range_m must be finite and >= 0");
  }
  if (!(goal_bias >= 0.0 && goal_bias <= 1.0)) {
    throw InputError("RrtOptions: goal_bias must be in [0, 1]");
  }
  if (!(goal_tolerance_m >= 0.0f) || !std::isfinite(goal_tolerance_m)) {
    throw InputError("RrtOptions: goal_tolerance_m must be finite and >= 0");
  }
  if (shortcut.max_vertices < 2) throw InputError("RrtOptions: shortcut.max_vertices must be >= 2");
}

Eigen::AlignedBox3f esdfBounds(const EsdfMap& map) {
  Eigen::AlignedBox3f box;  // empty
  const float block_m = map.voxel_size_m * kBlockEdge;
  for (const auto& [b, block] : map.blocks) {
    box.extend(b.cast<float>() * block_m);
    box.extend((b + BlockIndex::Ones()).cast<float>() * block_m);
  }
  return box;
}

RrtPlanner::RrtPlanner(CollisionChecker& checker, const RrtOptions& options)
    : checker_(checker), options_(options) {
  options_.validate();
}

PlanResult RrtPlanner::plan(const PlanRequest& request) {
  validateRequest(request);
  const auto t0 = std::chrono::steady_clock::now();
  const double device_ms0 = deviceMs(checker_);
  CountingChecker checker(checker_);
  stats_ = {};
  PlanResult result;
  auto finish = [&](PlanResult r) {
    r.planning_ms =
        msSince(t0);
    r.collision_checks = checker.spheresTested();
    stats_.batches = checker.batches();
    stats_.device_ms = deviceMs(checker_) - device_ms0;
    return r;
  };
  result.message = endpointProblem(checker, options_, request);
  if (!result.message.empty()) return finish(result);

  std::vector<Eigen::Vector3f> path;
  if (checker.segmentFree(request.start_W, request.goal_W, request.radius_m, request.unknown)) {
    path = {request.start_W, request.goal_W};
  } else {
    internal::OmplSolution solution = internal::solveWithOmpl(checker, options_, request);
    stats_.iterations = solution.iterations;
    stats_.motions_checked = solution.motions_checked;
    if (!solution.solved) {
      result.message = solution.message;
      return finish(result);
    }
    path = std::move(solution.path_W);
    // The goal region has a tolerance: end exactly at the goal when that motion is free.
    if ((path.back() - request.goal_W).norm() > 0.0f) path.push_back(request.goal_W);
  }
  stats_.shortened_from_m = pathLength(path);
  path = shortcutPath(path, checker, request.radius_m, request.unknown, options_.shortcut);
  if (!checker.pathFree(path, request.radius_m, request.unknown)) {
    result.message = "the planned path failed the final capsule check";
    return finish(result);
  }
  result.success = true;
  result.path_W = std::move(path);
  result.length_m = pathLength(result.path_W);
  result.min_clearance_m = checker.minClearance(result.path_W);
  return finish(result);
}

}  // namespace strata::plan

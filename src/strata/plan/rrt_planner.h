#pragma once
// RRT* on OMPL (informed RRT* by default) for a spherical robot in the world frame, with every
// collision test through a CollisionChecker (host or device ESDF): a motion is valid when the
// robot's capsule along it is free (CollisionChecker::segmentFree: one batch, one device dispatch
// per motion), a state when the zero-length capsule at it is (the sphere test at the capsule
// samples' radius: a start that passes is not then refused by every motion from it because the
// motions' samples are a little larger). Plain RRT*'s
// uniform samples are drawn in batches and pre-tested in one call each. After OMPL's solve, the
// path is shortened with batched capsule checks (path_shortcut.h) and checked once more as a
// whole. docs/plan.md "RRT* (OMPL)".
//
// Reproducibility: OMPL draws from a process-wide seed generator. plan() seeds it with
// PlanRequest::seed and builds every OMPL object (space, samplers, planner, nearest-neighbour
// structure) afterwards, so with RrtOptions::max_iterations set (and reached before the time
// budget) the same seed, map and request give the same path. With the time budget alone the
// number of iterations, hence the path, depends on the machine's speed. Another thread creating
// OMPL random generators during plan() breaks this.
// Errors: InputError for bad options (constructor) or a non-finite start, goal or radius (plan()).
// Thread safety: not thread safe (the checker and OMPL's global seed); one planner per thread.
#include <Eigen/Geometry>
#include <cstdint>

#include "strata/plan/collision_checker.h"
#include "strata/plan/path_shortcut.h"
#include "strata/plan/plan_types.h"

namespace strata::plan {

enum class RrtKind {
  kInformedRrtStar,  // RRT* that samples only where a shorter path can lie once it has one
  kRrtStar,          // plain RRT* (uniform samples for the whole budget)
};

struct RrtOptions {
  /// Box the robot's centre is sampled in (world frame, metres). Required, non-empty; e.g.
  /// esdfBounds(map): beyond the allocated map every sphere test fails under kOccupied anyway.
  Eigen::AlignedBox3f bounds_W;
  RrtKind kind = RrtKind::kInformedRrtStar;
  /// Longest motion added to the tree (metres); longer motions cost more sphere tests per check
  /// but explore faster. 0: OMPL's default (a fifth of the bounds' diagonal).
  float range_m = 1.0f;
  /// Share of samples drawn at the goal: faster first solutions, less exploration.
  double goal_bias = 0.05;
  /// The goal is reached within this distance of it (metres); the path then ends at the goal.
  float goal_tolerance_m = 0.05f;
  /// 0: plan for the whole PlanRequest::time_budget_s. Else also stop after this many
  /// iterations, which makes runs reproducible per seed (see the file comment).
  std::uint64_t max_iterations = 0;
  /// Shortening after the solve (rounds 0: none).
  ShortcutOptions shortcut;

  /// Throws InputError naming the bad field.
  void validate() const;
};

/// What the last plan() did, beyond PlanResult.
struct RrtStats {
  std::uint64_t iterations = 0;       // OMPL iterations (termination checks)
  std::uint64_t motions_checked = 0;  // capsule tests asked by OMPL
  std::uint64_t batches = 0;          // calls into the checker (device: dispatches)
  double device_ms = 0.0;             // summed device time (DeviceCollisionChecker), else 0
  double shortened_from_m = 0.0;      // length of OMPL's path before shortening
};

/// Bounding box of the allocated blocks of `map` (world frame, metres); empty for an empty map.
Eigen::AlignedBox3f esdfBounds(const EsdfMap& map);

class RrtPlanner final : public Planner {
 public:
  /// `checker` must outlive the planner.
  RrtPlanner(CollisionChecker& checker, const RrtOptions& options);

  /// Failure (success false, message): start or goal not free or outside the bounds, or no path
  /// within the budget. A free straight line from start to goal is returned without sampling.
  PlanResult plan(const PlanRequest& request) override;
  std::string name() const override { return "rrt"; }
  const RrtStats& lastStats() const { return stats_; }
  const RrtOptions& options() const { return options_; }

 private:
  CollisionChecker& checker_;
  RrtOptions options_;
  RrtStats stats_;
};

}  // namespace strata::plan

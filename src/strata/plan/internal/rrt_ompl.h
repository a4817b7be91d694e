#pragma once
// Internal to RrtPlanner: the OMPL problem (space, validity, motion validator, sampler, planner)
// and its solve, kept behind a header without OMPL types so OMPL stays private to the .cpp.
#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "strata/plan/collision_checker.h"
#include "strata/plan/plan_types.h"
#include "strata/plan/rrt_planner.h"

namespace strata::plan::internal {

struct OmplSolution {
  bool solved = false;
  std::vector<Eigen::Vector3f> path_W;  // start ... goal when solved
  std::string message;                  // why not solved
  std::uint64_t iterations = 0;
  std::uint64_t motions_checked = 0;
};

/// Seeds OMPL with request.seed, builds the problem and runs the planner until the budget or
/// the iteration cap. Start and goal must be valid and inside the bounds.
OmplSolution solveWithOmpl(CollisionChecker& checker, const RrtOptions& options,
                           const PlanRequest& request);

}  // namespace strata::plan::internal

#pragma once
// What an exploration planner sees and decides at each planning step of the exploration loop
// (exploration_loop.h): the robot's pose, a collision checker on the current ESDF and a gain
// oracle (how much unknown volume a view would see); it returns the waypoints to fly next.
// Planners: NbvpPlanner (nbvp_planner.h, the baseline), HistoryPlanner (history_planner.h).
// Frames: world (z up), metres; yaw counter-clockwise about +z from +x, radians.
#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "strata/explore/robot_model.h"
#include "strata/explore/view_gain.h"
#include "strata/plan/collision_checker.h"

namespace strata::explore {

/// View gains of a batch of positions (one device dispatch in the loop: ViewGainKernel::run).
using GainOracle = std::function<std::vector<ViewGain>(const std::vector<Eigen::Vector3f>&)>;

/// Valid for one plan() call.
struct ExplorationState {
  double sim_time_s = 0.0;
  RobotPose pose;
  /// Paths are flown only through known free space: capsules of this radius (the robot's radius
  /// plus a margin for the ESDF's discretisation) tested with UnknownPolicy::kOccupied.
  float check_radius_m = 0.4f;
  /// Where the robot may go (e.g. the world's bounds, shrunk by the robot's radius).
  Eigen::AlignedBox3f bounds_W;
  plan::CollisionChecker* checker = nullptr;
  GainOracle gain;
  /// The gain model's field of view and bins (gainAtYaw needs them).
  ViewGainConfig gain_config;
};

struct ExplorationStep {
  /// Waypoints to fly from the current pose (empty: hover and ask again).
  std::vector<Waypoint> path;
  /// The planner finds no gain anywhere: exploration is over.
  bool finished = false;
  /// "local" (receding-horizon step), "global" (to a cached view), "continue" (rest of a global
  /// path), "back" (no free edge from here twice: back along the route flown here), "turn" (no
  /// free edge twice and no route flown yet: turn in place to look around), "none".
  std::string mode = "none";
  /// Best single-view gain the step found (m^3).
  float best_gain_m3 = 0.0f;
  std::size_t tree_nodes = 0;
  /// Positions whose gain the step evaluated.
  std::size_t gain_evaluations = 0;
};

/// Thread safety: not thread safe.
class ExplorationPlanner {
 public:
  virtual ~ExplorationPlanner() = default;
  virtual ExplorationStep plan(const ExplorationState& state) = 0;
  /// "history" or "nbvp".
  virtual std::string name() const = 0;
};

}  // namespace strata::explore

#pragma once
// Closed-loop exploration in the simulator: a MAV (robot_model.h) with an RGB-D camera along its
// yaw, nodding up and down by camera_pitch_rad from frame to frame, flies what an
// ExplorationPlanner asks; frames are rendered from session 0 of a world and fused by a Mapper
// (TSDF with free space, incremental ESDF) at the camera rate; the ESDF is brought up to date
// before each planning step; the planner is asked when the robot has
// flown its path, or every replan period at a waypoint. Paths go through known free space only
// (kOccupied capsules of radius + margin). The run stops at the time limit, when the explored
// share of the reachable free space reaches the target, when the planner finds no gain anywhere,
// or when it has had nothing to fly for max_idle_steps steps in a row.
// Start clearing: the free space around the start (a vertical cylinder, voxels free in truth) is
// entered in the map as observed before the first frame, as NBVP clears a box around its start:
// the camera (+-47 degrees about the horizon over two frames) cannot see the space just above
// and below the robot, and without it no path could leave the start under kOccupied. Voxels of
// the cylinder near a solid stay unknown. The loop refuses a start closer than
// startClearanceNeeded to a surface.
// Time is simulated; compute times are wall clock.
// Thread safety: not thread safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "strata/explore/exploration_planner.h"
#include "strata/explore/exploration_truth.h"
#include "strata/explore/robot_model.h"
#include "strata/explore/view_gain.h"
#include "strata/mapper/mapper.h"
#include "strata/sim/world/world.h"
#include "strata/vk/vk.h"

namespace strata::explore {

struct ExplorationConfig {
  RobotConfig robot;
  /// Added to the robot's radius in the planners' collision checks (metres), at least
  /// kMarginVoxels voxels (checkRadius()): the ESDF knows obstacles to the voxel centre, the true
  /// surface can be half a voxel diagonal (0.87 voxel) nearer, and noisy depth blurs thin parts.
  float collision_margin_m = 0.05f;
  static constexpr float kMarginVoxels = 1.0f;
  /// Robot radius + the margin: the radius of every collision check of the planners.
  float checkRadius() const;
  /// Voxel of the map (metres). `strata explore` and the example use defaultVoxelSize(world):
  /// 5 cm for worlds as small as the office, whose 0.9 m doors 10 cm voxels do not pass.
  float voxel_size_m = 0.1f;
  /// The simulated camera: a smaller image renders and fuses faster; the field of view
  /// follows the gain model's (horizontal_fov_rad; the vertical one from the aspect ratio:
  /// 46.8 degrees at 160 x 120).
  int camera_width_px = 160;
  int camera_height_px = 120;
  /// A nodding camera: frames alternate between this pitch up and this pitch down (radians,
  /// 0: horizontal), so that two frames in a row tile +-(pitch + half the vertical field of
  /// view); at 0.41 rad they cover +-46.8 degrees, and the gain model's vertical field of view
  /// (coarseGain) is that. A horizontal camera sees nothing above 3.2 m from 1.2 m at 5 m range,
  /// and the space above the robot only from far off: a 5 m hall's upper third went unseen.
  float camera_pitch_rad = 0.41f;
  float camera_min_range_m = 0.3f;
  float camera_max_range_m = 5.0f;
  double camera_rate_hz = 5.0;
  double replan_period_s = 1.0;
  double time_limit_s = 600.0;
  /// Stop once this share of the reachable free volume is observed.
  double target_fraction = 0.99;
  /// The explored share is evaluated (and the curve sampled) every this many simulated seconds.
  double eval_period_s = 5.0;
  /// Simulation step of the robot's motion (seconds).
  double motion_step_s = 0.05;
  /// The cleared cylinder: the camera sees the space above and below a check capsule (radius +
  /// margin) only from about (radius + margin) / tan(vertical fov / 2) ~ 0.92 m away.
  float start_clearing_radius_m = 1.0f;
  float start_clearing_half_height_m = 0.45f;
  /// Depth endpoints seen from 3 places also block the planners' checks (surface_hits.h): thin
  /// parts (2.5 cm shelf boards) that the TSDF at 10 cm loses. false: the ESDF alone.
  bool surface_hits = true;
  /// In flight, after every fused frame, the path ahead (inflight_lookahead_m of it) is checked
  /// again against the surface hits of that frame and the ESDF of the last planning step (which
  /// passed it through space seen free), with the robot's radius + half the margin, or the robot's
  /// radius where the robot is already closer than that to something (it may fly
  /// away from it, not nearer): blocked, the robot brakes to rest and the planner is asked
  /// again. false: paths are flown as planned.
  bool inflight_checks = true;
  float inflight_lookahead_m = 2.0f;
  /// Steps in a row with nothing to fly before the run stops ("stuck").
  int max_idle_steps = 10;
  /// The gain model of both planners: 10-degree bins, 8 elevation rays (coarser than the
  /// kernel's defaults: a planning step evaluates 40-160 views).
  ViewGainConfig gain = coarseGain();
  /// Noise of the rendered frames.
  std::uint64_t seed = 1;

  static ViewGainConfig coarseGain();
  /// Throws InputError naming the bad field.
  void validate() const;
};

struct CurvePoint {
  double sim_time_s = 0.0;
  double explored_fraction = 0.0;
  double path_length_m = 0.0;
  /// Mean planning-step compute time since the previous point (wall ms; 0: no step).
  double compute_ms = 0.0;
};

struct StepRecord {
  double sim_time_s = 0.0;
  double compute_ms = 0.0;  // planner (wall)
  double esdf_ms = 0.0;     // ESDF update before it (wall)
  std::string mode;
  float best_gain_m3 = 0.0f;
  std::size_t tree_nodes = 0;
  std::size_t gain_evaluations = 0;
};

/// The closest approach of one collision: a contiguous stretch of the flown path closer to the
/// true geometry than the robot's radius.
struct CollisionEvent {
  double time_s = 0.0;  // simulated, of the closest sample
  Eigen::Vector3f p_W = Eigen::Vector3f::Zero();
  float clearance_m = 0.0f;  // true distance to the nearest surface there
};

struct ExplorationResult {
  std::string planner;
  std::vector<CurvePoint> curve;
  std::vector<StepRecord> steps;
  /// Positions flown, at most one motion step (<= 0.05 m at 1 m/s) apart.
  std::vector<Eigen::Vector3f> flown_W;
  /// Simulated time of each of flown_W (seconds).
  std::vector<double> flown_time_s;
  double path_length_m = 0.0;
  /// Contiguous stretches of the flown path whose true clearance is below the robot's radius,
  /// in time order.
  std::vector<CollisionEvent> collision_events;
  int collisions() const { return static_cast<int>(collision_events.size()); }
  /// Surface hits (ExplorationConfig::surface_hits): obstacle points at the end, and sphere
  /// tests the ESDF passed but the hits refused.
  std::size_t hit_obstacles = 0;
  std::uint64_t spheres_refused_by_hits = 0;
  float min_clearance_m = 0.0f;
  /// In-flight checks (ExplorationConfig::inflight_checks): checks made, brakes they caused,
  /// their wall time including the ESDF refresh before each (ms, total).
  std::size_t inflight_checks = 0;
  std::size_t brakes = 0;
  double inflight_ms = 0.0;
  double sim_time_s = 0.0;
  double wall_s = 0.0;
  double explored_fraction = 0.0;
  /// The share of the reachable volume entered by the start clearing (not seen by the camera).
  double start_clearing_fraction = 0.0;
  std::size_t reachable_voxels = 0;
  std::string stop_reason;  // "target", "time limit", "no gain", "stuck"
};

using ExplorationProgress = std::function<void(const CurvePoint& point, const StepRecord* last)>;

class ExplorationLoop {
 public:
  /// `world`, `truth` and `context` must outlive the loop. InputError for a bad config or a
  /// start without the cleared volume free.
  ExplorationLoop(const sim::World& world, const ExplorationTruth& truth,
                  const ExplorationConfig& config, const RobotPose& start, vk::Context& context);
  ~ExplorationLoop();

  /// Runs to a stop (once per loop object).
  ExplorationResult run(ExplorationPlanner& planner, const ExplorationProgress& progress = {});

  Mapper& mapper() { return *mapper_; }
  /// Where planners may go: the world's bounds shrunk by the robot's radius.
  const Eigen::AlignedBox3f& bounds() const { return bounds_W_; }

 private:
  struct Impl;
  void fuseFrame(double sim_time_s, std::uint64_t index);
  /// Brings the ESDF and the checkers up to date; the checker the planners use.
  plan::CollisionChecker& refreshChecker();
  /// The in-flight check: true when the path ahead is blocked.
  bool pathAheadBlocked();

  const sim::World& world_;
  const ExplorationTruth& truth_;
  ExplorationConfig config_;
  RobotPose start_;
  vk::Context& context_;
  Eigen::AlignedBox3f bounds_W_;
  std::unique_ptr<Mapper> mapper_;
  std::unique_ptr<Impl> impl_;
};

/// A start for `world`: the point nearest the centre of its first room, at height_m, at least
/// startClearanceNeeded from every surface (searched on a 0.1 m grid over that room).
/// InputError when the room holds none.
Eigen::Vector3f defaultStart(const sim::World& world, float height_m,
                             const ExplorationConfig& config);
/// The true clearance a start needs: the check radius and 0.2 m (metres).
float startClearanceNeeded(const ExplorationConfig& config);

/// The default voxel for exploring `world` (metres): kFineVoxelM where a grid of it over the
/// world's bounds holds at most kFineVoxelBudget voxels, else kCoarseVoxelM. At 10 cm a 0.9 m
/// door does not pass the 0.4 m check radius (the ESDF's sites lie up to a voxel in front of the
/// true surfaces, and the margin is a voxel); at 5 cm it does, at ~8x the map's voxels.
inline constexpr float kFineVoxelM = 0.05f;
inline constexpr float kCoarseVoxelM = 0.1f;
inline constexpr double kFineVoxelBudget = 4.0e6;
float defaultVoxelSize(const sim::World& world);

/// The camera-to-world pose of the robot's camera: optical axis along the yaw, pitched up by
/// pitch_rad (negative: down), image x to the right of the heading.
Eigen::Isometry3d cameraPose(const RobotPose& pose, float pitch_rad = 0.0f);
/// The pitch of frame `index` of the nodding camera: +pitch for even frames, -pitch for odd.
float framePitch(const ExplorationConfig& config, std::uint64_t index);

}  // namespace strata::explore

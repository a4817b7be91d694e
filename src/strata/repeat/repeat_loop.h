#pragma once
// Repeat: the closed loop that flies a taught path (taught_path.h) again in a later session of a
// simulated world, where objects may have moved.
// The robot: its true state (position, yaw) moves as commanded in its own body frame, at most
// max_speed / max_accel / max_yaw_rate (explore's RobotConfig). It knows only its estimate: the
// odometry (the true motion with online drift, online_drift.h, a seed of its own) fused with
// localisations against the teach map (localize::PoseFusion over localize::Localizer), every
// localize_every-th camera frame. Before the fusion has initialised, and in a run without
// localisation, the estimate is the odometry with T_M_O = identity: the repeat starts where the
// teach started, whose first odometry pose was exact, so the map frame and the odometry frame
// coincide there. The follower (path_follower.h) commands the ESTIMATE along the taught path;
// the true path differs by the estimate's error.
// Live mapping: every camera frame (rendered at the TRUE pose in the repeat session) is fused by
// a Mapper (TSDF with free space, every frame weighing 1, ESDF over voxels seen by
// esdf_min_weight frames) at the ESTIMATED pose. Every esdf_period_s the ESDF is updated and the
// follower's path ahead (check_ahead_m) is checked: a point is blocked where the live map holds a
// surface within check_radius_m that the teach map held change_margin_m farther (the teach map:
// the teach keyframes fused at their map poses, all of them or those taught near the progress
// point, teach_window_m; a place the teach passed twice holds two differently drifted copies of
// its walls). Where the teach map does not know
// the point nothing blocks; unknown space counts as free (the taught path was flown, the live map
// only adds what has appeared). A block counts once two checks in a row see it. Blocked: the
// robot brakes, then plans a detour with grid A* on the live map from the estimate to the first
// free taught point past the block, through space the live map has seen free (the robot's
// radius, then 3/4 of it); without one it stops and says why (RepeatResult::stop_reason).
// Scoring (truth, never seen by the robot): following error = distance from each true position
// to the polyline of the teach's true positions; drift = |estimate - truth| of the camera
// centre; collisions = stretches with true clearance in the repeat session below the radius.
// Frames: map M (= teach odometry = world at the start), world W; metres, seconds, radians.
// Errors: InputError for bad settings or a session the world lacks.
// Thread safety: not thread safe; `world`, `map`, `context` must outlive the loop.
#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "strata/localize/localizer.h"
#include "strata/localize/pose_fusion.h"
#include "strata/repeat/path_follower.h"
#include "strata/repeat/teach_recording.h"
#include "strata/vk/vk.h"

namespace strata::repeat {

struct RepeatConfig {
  explore::RobotConfig robot = RouteConfig::defaultRobot();
  CameraSetup camera;
  double camera_rate_hz = 5.0;
  double motion_step_s = 0.05;
  /// Localise every this many frames; 0: no localisation (odometry alone).
  int localize_every = 2;
  /// Localise against the teach keyframes taught from window_behind_m behind to window_ahead_m
  /// ahead of the progress point only (rebuilt every window_step_m of progress): a place the
  /// teach passed twice was mapped twice with different odometry drift, and the pass being
  /// repeated is the one to follow. Both 0: the whole map.
  double window_behind_m = 2.0;
  double window_ahead_m = 4.0;
  double window_step_m = 1.0;
  /// The repeat's VIO drift (its own seed).
  sim::DriftConfig drift = TeachConfig::defaultDrift();
  std::uint64_t seed = 2;
  FollowerConfig follower;
  localize::LocalizerConfig localizer;
  localize::FusionConfig fusion = defaultFusion();
  /// The live map's voxel (metres).
  float voxel_size_m = 0.05f;
  double esdf_period_s = 1.0;
  /// Frames a voxel needs to count in the ESDF (the live map weighs every frame 1).
  float esdf_min_weight = 3.0f;
  float check_ahead_m = 2.0f;
  /// A new surface nearer the path ahead than this blocks it (metres). Below the robot's radius
  /// (0.3): the ESDF's 5 cm voxels read a surface up to 4 cm nearer than it is, and in the office
  /// objects moved to 0.32 m from the taught path were flagged at 0.3.
  float check_radius_m = 0.25f;
  /// With the teach map given, a point ahead is blocked only where the live map holds a surface
  /// within the check radius that is this much nearer than the teach map's (metres): walls the
  /// taught path passed closely (0.9 m doors) are no block, a moved object is. Where the teach
  /// map does not know the point, nothing blocks (the drifted map frame put walls the teach never
  /// saw across the taught path in the office). (0.1 m flagged walls seen through the
  /// estimate's few centimetres of error: false blocks in the office.)
  float change_margin_m = 0.2f;
  /// > 0: the teach map of the check holds only the keyframes taught from this far behind to
  /// twice this far ahead of the progress point (rebuilt every window_step_m); 0: all of them.
  /// 3 m missed a crate moved onto the warehouse path on the first pass (its place was unknown
  /// to the smaller map) and still false-blocked the office: 0 by default.
  double teach_window_m = 0.0;
  /// A block is acted on once two checks in a row find one within this distance of each other
  /// (metres; the robot flies on meanwhile: check_ahead_m leaves room to brake).
  float block_confirm_m = 0.5f;
  /// The run stops after this long without progress along the path, or at the time limit
  /// (0: 3 x the taught length / max speed + 60 s).
  double stuck_after_s = 30.0;
  double time_limit_s = 0.0;
  /// Live mapping, checks and detours; false: the taught path is flown blind.
  bool live_map = true;
  /// Non-empty: the live map is saved there at the end (Mapper::save).
  std::string save_map_path;

  static localize::FusionConfig defaultFusion();
  void validate() const;
};

struct LocalizationRecord {
  double t_s = 0.0;
  bool localized = false;
  bool accepted = false;  // by the fusion
  std::string note;       // the localiser's or the fusion's reason when not accepted
  double time_ms = 0.0;
};

struct RepeatStop {
  double t_s = 0.0;
  Eigen::Vector3f p_W = Eigen::Vector3f::Zero();  // true position
  std::string reason;
  bool resumed = false;  // a detour was found and flown
};

struct Collision {
  double t_s = 0.0;
  Eigen::Vector3f p_W = Eigen::Vector3f::Zero();
  float clearance_m = 0.0f;
};

struct RepeatResult {
  bool localization = false;
  std::vector<double> t_s;                  // per motion step
  std::vector<Eigen::Vector3f> true_W;      // true camera centres
  std::vector<Eigen::Vector3f> estimate_M;  // estimated camera centres
  std::vector<float> following_error_m;     // per step (true position vs taught truth)
  double following_rms_m = 0.0, following_max_m = 0.0;
  double drift_final_m = 0.0, drift_max_m = 0.0;  // |estimate - truth|
  double odometry_drift_final_m = 0.0;            // |odometry - truth| at the end
  double path_length_m = 0.0;                     // flown (truth)
  double taught_length_m = 0.0;
  double progress_m = 0.0;  // along the taught path at the end
  std::vector<LocalizationRecord> localizations;
  std::size_t localized = 0, accepted = 0, rejected = 0;
  double localize_ms_mean = 0.0, localize_ms_max = 0.0;
  std::vector<RepeatStop> stops;
  std::vector<Collision> collisions;
  float min_clearance_m = 0.0f;
  std::size_t detours = 0;
  bool finished = false;    // reached the end of the taught path
  std::string stop_reason;  // "end of the taught path", "blocked: ...", "time limit", ...
  double sim_time_s = 0.0, wall_s = 0.0;
};

/// Progress on stderr-like sinks: simulated time, progress along the path, the last result.
using RepeatProgress =
    std::function<void(double t_s, double progress_m, double length_m, const RepeatResult& so_far)>;

/// Runs one repeat of `taught` in `session` of `world`. `map` may be null only with
/// config.localize_every == 0 (the path-ahead check then sees every surface near the path as a
/// block).
RepeatResult runRepeat(const sim::World& world, int session, const TaughtPath& taught,
                       const localize::PriorMap* map, const RepeatConfig& config,
                       vk::Context& context, const RepeatProgress& progress = {});

/// Fills the scores of `result` (following error, drift) from its samples; collisions from the
/// repeat session's truth.
void scoreRepeat(RepeatResult& result, const TaughtPath& taught);

}  // namespace strata::repeat

#pragma once
// The state of one repeat run (repeat_loop.cpp, repeat_step.cpp).
#include <memory>
#include <optional>

#include "strata/mapper/mapper.h"
#include "strata/plan/collision_checker.h"
#include "strata/repeat/online_drift.h"
#include "strata/repeat/repeat_loop.h"
#include "strata/sim/sensors/rgbd_camera.h"

namespace strata::repeat {

class RepeatRun {
 public:
  RepeatRun(const sim::World& world, int session, const TaughtPath& taught,
            const localize::PriorMap* map, const RepeatConfig& config, vk::Context& context);
  RepeatResult run(const RepeatProgress& progress);

 private:
  /// Renders the frame at the true pose, fuses it at the estimate, localises it when due.
  void frame(double t_s, std::uint64_t index);
  void localize(const RgbdFrame& frame, double t_s);
  /// The localiser over the teach keyframes near the progress point (rebuilt as it moves).
  const localize::Localizer& localWindow();
  /// Moves the true robot by one step of the command; the odometry and the estimate follow.
  void move(const FollowerCommand& command, double t_s);
  /// The estimate from the odometry (and the fusion once initialised).
  void updateEstimate(const localize::FusedPose& fused);
  /// Checks the path ahead on a fresh ESDF; on a block, brakes and tries a detour. False: the
  /// run must stop (result_.stop_reason says why).
  bool checkAhead(double t_s);
  /// The teach keyframes taught near the progress point fused at their map poses (rebuilt as
  /// the progress moves): what the teach saw there, in the frame of the pass being repeated.
  Mapper& teachWindow();
  bool planDetour(double t_s, const Eigen::Vector3f& blocked_M, double blocked_s);
  void record(double t_s);

  const sim::World& world_;
  const TaughtPath& taught_;
  const localize::PriorMap* map_;
  RepeatConfig config_;
  vk::Context& context_;
  std::unique_ptr<sim::WorldScene> scene_;
  sim::RgbdCamera camera_;
  sim::Lighting lighting_;
  bool localizing_ = false;
  std::vector<double> keyframe_s_;  // taught arc length of each map keyframe
  std::unique_ptr<localize::PriorMap> window_map_;
  std::unique_ptr<localize::Localizer> window_localizer_;
  double window_centre_m_ = 0.0;
  localize::PoseFusion fusion_;
  OnlineDrift drift_;
  PathFollower follower_;
  std::unique_ptr<Mapper> mapper_;
  std::unique_ptr<Mapper> teach_map_;  // the teach keyframes near the progress point
  double teach_centre_m_ = 0.0;
  std::optional<Eigen::Vector3f> pending_block_;  // seen by the last check, not yet confirmed
  std::unique_ptr<plan::DeviceCollisionChecker> checker_;
  // Truth: position and yaw of the robot; its velocity in the estimate's (map) axes.
  Eigen::Vector3f p_W_ = Eigen::Vector3f::Zero();
  float yaw_W_ = 0.0f;
  Eigen::Vector3f v_M_ = Eigen::Vector3f::Zero();
  Eigen::Isometry3d T_O_C_ = Eigen::Isometry3d::Identity();  // odometry
  Eigen::Isometry3d T_M_C_ = Eigen::Isometry3d::Identity();  // estimate
  bool in_collision_ = false;
  RepeatResult result_;
};

/// The robot's camera pose (horizontal, along the yaw).
Eigen::Isometry3d robotCamera(const Eigen::Vector3f& p_W, float yaw_rad);
/// Yaw of a camera pose's optical axis about +z.
float yawOf(const Eigen::Isometry3d& T_W_C);

}  // namespace strata::repeat

#pragma once
// Internal to VioEstimator: the keyframes and landmarks of the sliding window, the factor graph
// built from them for one solve, and the marginalisation of the oldest keyframe.
#include <ceres/loss_function.h>
#include <ceres/solver.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <unordered_map>
#include <vector>

#include "strata/odometry/camera_rig.h"
#include "strata/odometry/frame_observations.h"
#include "strata/odometry/marginalization.h"
#include "strata/odometry/preintegration.h"
#include "strata/odometry/state_parameters.h"

namespace strata::odometry::internal {

struct Keyframe {
  std::int64_t id = 0;
  double t_s = 0.0;
  double pose[kPoseSize] = {0, 0, 0, 1, 0, 0, 0};  // q_W_B (x, y, z, w), p_W_B
  double speed_bias[kSpeedBiasSize] = {};          // v_W_B, b_g, b_a
  /// From the previous keyframe to this one (null for the first of the window).
  std::shared_ptr<Preintegration> from_previous;

  Eigen::Isometry3d T_W_B() const;
  void setPose(const Eigen::Matrix3d& R_W_B, const Eigen::Vector3d& p_W_B);
  Eigen::Vector3d velocity() const { return Eigen::Vector3d(speed_bias); }
  ImuBias bias() const;
};

struct Observation {
  std::int64_t keyframe_id = 0;
  Eigen::Vector2d uv_left;  // pixels of the rig's pinhole model (undistorted)
  std::optional<Eigen::Vector2d> uv_right;
};

struct Landmark {
  std::int64_t anchor_id = 0;  // keyframe of the first observation
  Eigen::Vector3d bearing;     // left-camera ray of that observation, z = 1
  double rho = 0.0;            // inverse depth (1/m); 0: not triangulated yet
  std::vector<Observation> observations;
};

enum class FactorKind { kImu, kReprojection, kPrior };

struct Factor {
  std::unique_ptr<ceres::CostFunction> owned;  // null for the prior (owned by the window)
  const ceres::CostFunction* cost = nullptr;
  const ceres::LossFunction* loss = nullptr;
  std::vector<double*> blocks;
  FactorKind kind = FactorKind::kImu;
  std::uint64_t track_id = 0;    // reprojection: the landmark
  std::int64_t keyframe_id = 0;  // reprojection: the observing keyframe; IMU: the later one
  double sigma_px = 1.0;
};

struct SolveSettings {
  double pixel_sigma_px = 1.0;
  double huber_px = 2.0;
  int max_iterations = 6;
  double max_solver_time_s = 0.03;
  Eigen::Vector3d gravity_W = Eigen::Vector3d(0.0, 0.0, -9.81);
  bool visual_only = false;  // no IMU factors or prior; the first pose held constant
};

class Window {
 public:
  /// huber_whitened: Huber threshold in units of the pixel sigma.
  Window(const CameraRig& rig, double huber_whitened);

  std::deque<Keyframe> keyframes;  // deque: element addresses stay valid at both ends
  std::unordered_map<std::uint64_t, Landmark> landmarks;
  std::unique_ptr<LinearPrior> prior;

  void clear();
  Keyframe& keyframe(std::int64_t id) { return keyframes[index(id)]; }
  const Keyframe& keyframe(std::int64_t id) const { return keyframes[index(id)]; }
  bool contains(std::int64_t id) const {
    return !keyframes.empty() && id >= keyframes.front().id && id <= keyframes.back().id;
  }
  Eigen::Isometry3d T_W_C(std::int64_t keyframe_id, bool right) const;
  /// Adds the frame's observations to keyframe `id` (new tracks start new landmarks there).
  void addObservations(std::int64_t id, const std::vector<FeatureObservation>& features);
  /// Gives untriangulated landmarks an inverse depth from all their rays in the window (linear
  /// least squares) when the depth lands in [min_depth, max_depth] in every observing camera.
  void triangulate(double min_depth_m, double max_depth_m);
  /// The factors of one solve; pointers into this window stay valid until it changes.
  std::vector<Factor> buildFactors(const SolveSettings& settings) const;
  ceres::Solver::Summary solve(const std::vector<Factor>& factors, const SolveSettings& settings);
  /// Reprojection error (px) of a reprojection factor at the current estimate.
  static double reprojectionErrorPx(const Factor& factor);
  /// Drops observations with error above outlier_px and landmarks left with one keyframe or a
  /// non-positive inverse depth.
  void removeOutliers(const std::vector<Factor>& factors, double outlier_px);
  /// Marginalises the oldest keyframe with the landmarks anchored in it into `prior`.
  void marginaliseOldest(const std::vector<Factor>& factors);
  const ceres::Manifold* poseManifold() const { return &pose_manifold_; }

 private:
  std::size_t index(std::int64_t id) const {
    return static_cast<std::size_t>(id - keyframes.front().id);
  }

  CameraRig rig_;
  PoseManifold pose_manifold_;
  std::unique_ptr<ceres::LossFunction> loss_;
};

}  // namespace strata::odometry::internal

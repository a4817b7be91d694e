#pragma once
// A smooth, dynamically feasible trajectory along a planned polyline (world frame, metres,
// seconds), for flying a spherical robot along a path. docs/plan.md "Trajectories".
//
// Method. Every interior vertex is rounded by a quadratic Bezier curve from p - d*u_in through
// the control point p to p + d*u_out (d at most half of each adjacent segment, so blends never
// overlap); its corner deviation (vertex to curve) is 0.5 * d * sin(turn / 2) and starts at the
// clearance margin at the vertex (ESDF distance minus radius). The geometry is sampled every
// `sample_step_m` of arc length and timed along it: speed <= v_max, tangential acceleration
// <= a_max and centripetal acceleration v^2 * curvature <= a_max at every sample (forward pass
// from rest at the start, backward pass to rest at the end). A vertex left sharp (d = 0) is a stop
// (speed 0 there), so the robot never turns at speed without a curve.
//
// Guarantee. The capsules (robot radius) between consecutive samples are tested with
// CollisionChecker::segmentsFree (one batch per attempt); a corner whose curve collides has its d
// halved and the trajectory is rebuilt, down to d = 0 (the polyline itself). collision_free says
// whether the returned samples passed that test; it is false only when the polyline resampled at
// the trajectory's samples fails the (slightly conservative) capsule test itself. Between samples
// the curve departs from the chord by at most step^2 * curvature / 8.
// Errors: InputError for an empty or non-finite path or bad limits.
// Thread safety: makeTrajectory is not thread safe (the checker); a Trajectory is a value.
#include <Eigen/Core>
#include <vector>

#include "strata/plan/collision_checker.h"

namespace strata::plan {

struct TrajectoryLimits {
  /// Speed limit (m/s).
  float v_max_mps = 1.0f;
  /// Tangential and centripetal acceleration limit, each (m/s^2).
  float a_max_mps2 = 1.0f;
  /// Arc length between samples (metres); 0: half the checker's voxel. Finer: closer limits
  /// and collision test, more samples.
  float sample_step_m = 0.0f;
  /// Halvings of a colliding corner's d before the corner is left sharp.
  int corner_retries = 6;

  /// Throws InputError naming the bad field.
  void validate() const;
};

struct TrajectorySample {
  double t_s = 0.0;
  Eigen::Vector3f p_W = Eigen::Vector3f::Zero();
  Eigen::Vector3f v_W = Eigen::Vector3f::Zero();  // m/s
  Eigen::Vector3f a_W = Eigen::Vector3f::Zero();  // m/s^2, tangential + centripetal
};

struct Trajectory {
  std::vector<TrajectorySample> samples;  // t_s increasing from 0 to duration_s
  double duration_s = 0.0;
  float max_speed_mps = 0.0f;          // over the samples
  float max_acceleration_mps2 = 0.0f;  // |a_W| over the samples
  /// Per interior vertex of the (deduplicated) path: distance from the vertex to the curve
  /// (metres); 0 where the corner is sharp (a stop) or straight.
  std::vector<float> corner_deviation_m;
  /// The capsules between consecutive samples passed the checker (see the header comment).
  bool collision_free = false;

  /// State at time t (clamped to [0, duration]): linear interpolation between samples.
  TrajectorySample at(double t_s) const;
};

/// `path_W`: e.g. PlanResult::path_W (repeated points are dropped; one point: at rest).
Trajectory makeTrajectory(const std::vector<Eigen::Vector3f>& path_W,
                          const TrajectoryLimits& limits, CollisionChecker& checker, float radius_m,
                          UnknownPolicy unknown);

}  // namespace strata::plan

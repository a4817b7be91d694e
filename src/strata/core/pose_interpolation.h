#pragma once
// Poses between stamped poses: translation linear, rotation by slerp. One rule for every sequence
// of timed poses (ground truth, odometry estimates), so they interpolate alike.
#include <Eigen/Geometry>
#include <algorithm>
#include <optional>

namespace strata {

/// The pose a fraction `s` of the way from T_a to T_b (s = 0: T_a, s = 1: T_b).
inline Eigen::Isometry3d interpolatePose(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b,
                                         double s) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(T_a.linear())
                   .slerp(s, Eigen::Quaterniond(T_b.linear()))
                   .toRotationMatrix();
  T.translation() = (1.0 - s) * T_a.translation() + s * T_b.translation();
  return T;
}

/// The pose at time `t` from `stamped`, a time-ordered range whose elements give their time by
/// `time_of(e)` and their pose by `pose_of(e)`: the pose of an element at exactly t, else the
/// interpolation between the two elements around t. nullopt outside the range's span or when
/// those two are more than `max_gap` apart.
template <class Range, class Time, class TimeOf, class PoseOf>
std::optional<Eigen::Isometry3d> interpolateStamped(const Range& stamped, Time t, Time max_gap,
                                                    TimeOf time_of, PoseOf pose_of) {
  const auto after = std::lower_bound(std::begin(stamped), std::end(stamped), t,
                                      [&](const auto& e, Time x) { return time_of(e) < x; });
  if (after == std::end(stamped)) return std::nullopt;
  if (time_of(*after) == t) return pose_of(*after);
  if (after == std::begin(stamped)) return std::nullopt;
  const auto& a = *(after - 1);
  const auto& b = *after;
  if (time_of(b) - time_of(a) > max_gap) return std::nullopt;
  const double s =
      static_cast<double>(t - time_of(a)) / static_cast<double>(time_of(b) - time_of(a));
  return interpolatePose(pose_of(a), pose_of(b), s);
}

}  // namespace strata

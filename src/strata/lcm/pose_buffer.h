#pragma once
// Camera poses by time, for frames that arrive without one: T_W_C at a frame's utime by linear
// interpolation of position and spherical interpolation of orientation between the two poses
// around it. Bounded: the oldest poses go first.
// Thread safety: not thread safe.
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>

namespace strata::lcm_io {

enum class PoseLookup {
  kFound,       // interpolated (or an exact stamp)
  kNotYet,      // utime is newer than the newest pose: a later pose may still bracket it
  kTooOld,      // utime is older than the oldest pose kept
  kGapTooLarge  // the poses around utime are further apart than max_gap_us
};

const char* describe(PoseLookup lookup);

class PoseBuffer {
 public:
  /// `capacity`: poses kept; `max_gap_us`: the most time between two poses interpolated across
  /// (a longer gap means the pose source stalled, and a guess would smear the map).
  explicit PoseBuffer(std::size_t capacity = 4096, std::int64_t max_gap_us = 500000);

  /// Throws InputError when utime is not newer than the newest pose (out-of-order stamp).
  void add(std::int64_t utime, const Eigen::Isometry3d& T_W_C);
  PoseLookup lookup(std::int64_t utime, Eigen::Isometry3d* T_W_C) const;
  std::size_t size() const { return poses_.size(); }

 private:
  struct Stamped {
    std::int64_t utime;
    Eigen::Vector3d t_W_C;
    Eigen::Quaterniond q_W_C;
  };
  std::size_t capacity_;
  std::int64_t max_gap_us_;
  std::deque<Stamped> poses_;
};

/// T_a at alpha = 0, T_b at alpha = 1.
Eigen::Isometry3d interpolatePose(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b,
                                  double alpha);

}  // namespace strata::lcm_io

#include "strata/lcm/pose_buffer.h"

#include <algorithm>
#include <string>

#include "strata/core/error.h"

namespace strata::lcm_io {
namespace {

Eigen::Isometry3d makePose(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = t;
  return T;
}

}  // namespace

const char* describe(PoseLookup lookup) {
  switch (lookup) {
    case PoseLookup::kFound:
      return "found";
    case PoseLookup::kNotYet:
      return "newer than every pose";
    case PoseLookup::kTooOld:
      return "older than every pose kept";
    case PoseLookup::kGapTooLarge:
      return "between poses too far apart to interpolate";
  }
  return "?";
}

PoseBuffer::PoseBuffer(std::size_t capacity, std::int64_t max_gap_us)
    : capacity_(std::max<std::size_t>(capacity, 2)), max_gap_us_(max_gap_us) {}

void PoseBuffer::add(std::int64_t utime, const Eigen::Isometry3d& T_W_C) {
  if (!poses_.empty() && utime <= poses_.back().utime) {
    throw InputError("pose utime " + std::to_string(utime) + " is not after the previous pose's " +
                     std::to_string(poses_.back().utime) + " (out of order)");
  }
  poses_.push_back({utime, T_W_C.translation(), Eigen::Quaterniond(T_W_C.rotation())});
  while (poses_.size() > capacity_) poses_.pop_front();
}

PoseLookup PoseBuffer::lookup(std::int64_t utime, Eigen::Isometry3d* T_W_C) const {
  if (poses_.empty() || utime > poses_.back().utime) return PoseLookup::kNotYet;
  if (utime < poses_.front().utime) return PoseLookup::kTooOld;
  const auto after =
      std::lower_bound(poses_.begin(), poses_.end(), utime,
                       [](const Stamped& pose, std::int64_t t) { return pose.utime < t; });
  if (after->utime == utime) {
    *T_W_C = makePose(after->t_W_C, after->q_W_C);
    return PoseLookup::kFound;
  }
  const Stamped& before = *(after - 1);
  if (after->utime - before.utime > max_gap_us_) return PoseLookup::kGapTooLarge;
  const double alpha =
      static_cast<double>(utime - before.utime) / static_cast<double>(after->utime - before.utime);
  *T_W_C = makePose(before.t_W_C + alpha * (after->t_W_C - before.t_W_C),
                    before.q_W_C.slerp(alpha, after->q_W_C));
  return PoseLookup::kFound;
}

Eigen::Isometry3d interpolatePose(const Eigen::Isometry3d& T_a, const Eigen::Isometry3d& T_b,
                                  double alpha) {
  const Eigen::Quaterniond q_a(T_a.rotation()), q_b(T_b.rotation());
  return makePose(T_a.translation() + alpha * (T_b.translation() - T_a.translation()),
                  q_a.slerp(alpha, q_b));
}

}  // namespace strata::lcm_io

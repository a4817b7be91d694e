#include "strata/odometry/frontend/keyframe_policy.h"

#include "strata/core/error.h"
#include "strata/odometry/frontend/geometric_check.h"

namespace strata::odometry {

void KeyframeConfig::validate() const {
  if (!(min_parallax_px > 0.0)) throw InputError("KeyframeConfig: min_parallax_px must be > 0");
  if (!(min_tracked_fraction >= 0.0 && min_tracked_fraction <= 1.0)) {
    throw InputError("KeyframeConfig: min_tracked_fraction must be in [0, 1]");
  }
  if (!(max_interval_s > 0.0)) throw InputError("KeyframeConfig: max_interval_s must be > 0");
}

KeyframePolicy::KeyframePolicy(KeyframeConfig config) : config_(config) { config_.validate(); }

bool KeyframePolicy::decide(std::int64_t timestamp_ns,
                            const std::vector<FeatureObservation>& features,
                            const std::optional<Eigen::Matrix3d>& R_cur_prev, double focal_px,
                            bool lost, double* parallax_px) {
  if (R_cur_keyframe_ && R_cur_prev) {
    R_cur_keyframe_ = *R_cur_prev * *R_cur_keyframe_;
  } else {
    R_cur_keyframe_.reset();
  }
  double parallax_sum = 0.0;
  int shared = 0;
  for (const FeatureObservation& f : features) {
    const auto it = reference_xy_.find(f.track_id);
    if (it == reference_xy_.end()) continue;
    parallax_sum +=
        rotationCompensatedParallaxPx(it->second, f.xy_left_norm, R_cur_keyframe_, focal_px);
    ++shared;
  }
  const double parallax = shared > 0 ? parallax_sum / shared : 0.0;
  *parallax_px = parallax;
  const double tracked_fraction =
      reference_xy_.empty() ? 0.0 : static_cast<double>(shared) / reference_xy_.size();
  const double interval_s = 1e-9 * static_cast<double>(timestamp_ns - keyframe_time_ns_);
  const bool keyframe = !has_keyframe_ || lost || parallax >= config_.min_parallax_px ||
                        tracked_fraction < config_.min_tracked_fraction ||
                        interval_s >= config_.max_interval_s;
  if (!keyframe) return false;
  has_keyframe_ = true;
  keyframe_time_ns_ = timestamp_ns;
  reference_xy_.clear();
  for (const FeatureObservation& f : features) reference_xy_[f.track_id] = f.xy_left_norm;
  R_cur_keyframe_ = Eigen::Matrix3d::Identity();
  return true;
}

}  // namespace strata::odometry

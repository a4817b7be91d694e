#include "strata/track/track_config.h"

#include <cmath>

#include "strata/core/error.h"

namespace strata {
namespace {

void require(bool condition, const std::string& message) {
  if (!condition) throw InputError("TrackConfig: " + message);
}

}  // namespace

void TrackConfig::validate() const {
  require(levels >= 1 && levels <= 6, "levels must be in [1, 6]");
  require(static_cast<int>(iterations.size()) == levels,
          "iterations must hold one count per level (" + std::to_string(levels) + ")");
  require(model_level >= 0 && model_level < levels, "model_level must be in [0, levels)");
  for (int n : iterations) require(n >= 1 && n <= 100, "iterations must be in [1, 100]");
  require(smoothing_sigma_px >= 0.0f && smoothing_sigma_px <= 8.0f,
          "smoothing_sigma_px must be in [0, 8]");
  require(smoothing_depth_share > 0.0f, "smoothing_depth_share must be > 0");
  require(pyramid_depth_threshold_m > 0.0f, "pyramid_depth_threshold_m must be > 0");
  require(max_distance_m > 0.0f, "max_distance_m must be > 0");
  require(max_normal_angle_deg > 0.0f && max_normal_angle_deg < 90.0f,
          "max_normal_angle_deg must be in (0, 90)");
  require(huber_m >= 0.0f, "huber_m must be >= 0");
  require(std::isfinite(color_weight) && color_weight >= 0.0, "color_weight must be >= 0");
  require(convergence_update >= 0.0, "convergence_update must be >= 0");
  require(min_inlier_fraction >= 0.0 && min_inlier_fraction <= 1.0,
          "min_inlier_fraction must be in [0, 1]");
  require(max_rms_m > 0.0, "max_rms_m must be > 0");
  require(min_eigenvalue >= 0.0, "min_eigenvalue must be >= 0");
  require(std::isfinite(covariance_scale) && covariance_scale > 0.0,
          "covariance_scale must be > 0");
  require(max_translation_jump_m > 0.0, "max_translation_jump_m must be > 0");
  require(max_rotation_jump_deg > 0.0, "max_rotation_jump_deg must be > 0");
}

}  // namespace strata

#include "strata/sim/analytic_dataset.h"

#include <cmath>
#include <string>

#include "strata/core/error.h"
#include "strata/sim/default_scene.h"

namespace strata::sim {

AnalyticDataset::AnalyticDataset(const AnalyticDatasetConfig& config)
    : AnalyticDataset(makeDefaultScene(), makeDefaultTrajectory(config.frame_count), config) {}

AnalyticDataset::AnalyticDataset(AnalyticScene scene, std::vector<Eigen::Isometry3d> poses_T_W_C,
                                 const AnalyticDatasetConfig& config)
    : scene_(std::move(scene)), poses_T_W_C_(std::move(poses_T_W_C)), config_(config) {
  config_.intrinsics.validate();
  if (!(config_.max_depth_m > 0.0f) || !std::isfinite(config_.max_depth_m)) {
    throw InputError("AnalyticDatasetConfig: max_depth_m must be finite and positive");
  }
  if (!(config_.frame_rate_hz > 0.0) || !std::isfinite(config_.frame_rate_hz)) {
    throw InputError("AnalyticDatasetConfig: frame_rate_hz must be finite and positive");
  }
  if (poses_T_W_C_.empty()) throw InputError("AnalyticDataset: no poses (empty trajectory)");
  for (std::size_t i = 0; i < poses_T_W_C_.size(); ++i) {
    validatePose(poses_T_W_C_[i], "AnalyticDataset pose " + std::to_string(i));
  }
}

std::string AnalyticDataset::name() const {
  return "analytic scene (" + std::to_string(scene_.primitiveCount()) + " primitives, " +
         std::to_string(poses_T_W_C_.size()) + " frames)";
}

RgbdFrame AnalyticDataset::load(std::size_t index) const {
  if (index >= poses_T_W_C_.size()) {
    throw InputError(name() + ": frame index " + std::to_string(index) + " out of range");
  }
  RgbdFrame frame;
  frame.timestamp_s = static_cast<double>(index) / config_.frame_rate_hz;
  frame.name = "analytic-" + std::to_string(index);
  frame.T_W_C = poses_T_W_C_[index];
  scene_.render(config_.intrinsics, frame.T_W_C, config_.max_depth_m, &frame.depth,
                config_.render_color ? &frame.color : nullptr);
  validateFrame(frame, config_.intrinsics);
  return frame;
}

}  // namespace strata::sim

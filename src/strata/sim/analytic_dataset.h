#pragma once
// A Dataset whose frames are rendered on demand from an AnalyticScene: exact depth, no noise.
#include <Eigen/Geometry>
#include <vector>

#include "strata/io/open_dataset.h"
#include "strata/sim/analytic_scene.h"

namespace strata::sim {

struct AnalyticDatasetConfig {
  /// Frames on the default trajectory (ignored when poses are given).
  int frame_count = 60;
  /// Default: 640x480, fx=fy=525, cx=319.5, cy=239.5.
  CameraIntrinsics intrinsics;
  /// Sensor range: farther surfaces render as invalid (0). The default room's walls are within
  /// ~4.5 m; the floor outside it reaches this limit at grazing angles.
  float max_depth_m = 6.0f;
  /// Frame i has timestamp i / frame_rate_hz.
  double frame_rate_hz = 30.0;
  /// Render shaded colour as well (false: frames have empty colour, rendering is faster).
  bool render_color = true;
};

/// Thread safety: load() may be called from several threads at once.
class AnalyticDataset : public Dataset {
 public:
  /// makeDefaultScene() seen from makeDefaultTrajectory(config.frame_count).
  explicit AnalyticDataset(const AnalyticDatasetConfig& config = {});
  /// Any scene and camera-to-world poses. Throws InputError for an invalid pose or config.
  AnalyticDataset(AnalyticScene scene, std::vector<Eigen::Isometry3d> poses_T_W_C,
                  const AnalyticDatasetConfig& config = {});

  std::string name() const override;
  std::size_t size() const override { return poses_T_W_C_.size(); }
  CameraIntrinsics intrinsics() const override { return config_.intrinsics; }
  RgbdFrame load(std::size_t index) const override;

  const AnalyticScene& scene() const { return scene_; }
  const std::vector<Eigen::Isometry3d>& poses() const { return poses_T_W_C_; }

 private:
  AnalyticScene scene_;
  std::vector<Eigen::Isometry3d> poses_T_W_C_;
  AnalyticDatasetConfig config_;
};

}  // namespace strata::sim

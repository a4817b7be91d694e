#pragma once
// Datasets read from disk (TUM RGB-D, 7-Scenes); the interface is core/dataset.h.
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "strata/core/dataset.h"
#include "strata/core/types.h"

namespace strata {

struct DatasetOptions {
  /// "auto" | "tum" | "7scenes". Auto: TUM when depth.txt is present, else 7-Scenes when
  /// frame-*.depth.png files are.
  std::string format = "auto";
  /// Optional camera YAML (width, height, fx, fy, cx, cy, depth_scale, depth_invalid) applied after
  /// the folder's own camera.yaml.
  std::string camera_file;
  /// Override the intrinsics from every file.
  std::optional<CameraIntrinsics> intrinsics;
  /// Override the depth PNG scale (units per metre) from every file.
  std::optional<double> depth_scale;
  /// Optional TUM trajectory file (camera-to-world, e.g. aligned odometry) whose poses a TUM
  /// folder's frames take instead of its groundtruth.txt's (same association). 7-Scenes folders
  /// refuse it (their poses are per-frame files).
  std::string trajectory_file;
  /// Read colour images (false: frames have empty colour, loading is faster).
  bool load_color = true;
};

/// Opens the dataset in folder `path` (format detection above). Throws InputError when the folder
/// is missing, is neither layout, has no usable frame, or its camera description is invalid.
std::unique_ptr<Dataset> openDataset(const std::string& path, const DatasetOptions& options = {});

}  // namespace strata

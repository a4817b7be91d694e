#pragma once
// Sequences of posed RGB-D frames read from disk (TUM RGB-D, 7-Scenes) or made on demand (sim/).
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "core/types.h"

namespace strata {

/// A finite, indexable sequence of RGB-D frames with camera-to-world poses.
/// Thread safety: load() is const and may be called from several threads at once.
class Dataset {
 public:
  virtual ~Dataset();
  /// For messages: the format and folder, e.g. "TUM RGB-D '/data/redkitchen'".
  virtual std::string name() const = 0;
  virtual std::size_t size() const = 0;
  virtual CameraIntrinsics intrinsics() const = 0;
  /// Frame `index` in [0, size()), validated (validateFrame). Depth in metres, 0 = invalid; colour
  /// may be empty. Throws InputError naming the file and the problem.
  virtual RgbdFrame load(std::size_t index) const = 0;
  /// What was tolerated while opening (dropped frames, frames without colour), one line each;
  /// "" when nothing was.
  virtual std::string warnings() const { return {}; }
};

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
  /// Read colour images (false: frames have empty colour, loading is faster).
  bool load_color = true;
};

/// Opens the dataset in folder `path` (format detection above). Throws InputError when the folder
/// is missing, is neither layout, has no usable frame, or its camera description is invalid.
std::unique_ptr<Dataset> openDataset(const std::string& path, const DatasetOptions& options = {});

}  // namespace strata

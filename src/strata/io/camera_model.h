#pragma once
// How a dataset's depth camera is described: pinhole intrinsics plus the depth PNG encoding.
// Sources, later ones overriding earlier ones (see resolveCameraModel):
//   format defaults -> camera.yaml in the dataset folder -> DatasetOptions::camera_file
//   -> DatasetOptions::intrinsics / depth_scale.
#include <cstdint>
#include <istream>
#include <string>
#include <vector>

#include "strata/core/types.h"
#include "strata/io/open_dataset.h"

namespace strata {

struct CameraModel {
  CameraIntrinsics intrinsics;
  /// PNG units per metre (TUM: 5000, 7-Scenes: 1000).
  double depth_scale = 5000.0;
  /// Raw PNG values that mark an invalid pixel; 0 is always invalid.
  std::vector<std::uint16_t> depth_invalid{0};
  /// Where the values came from, for messages ("defaults", a file name...).
  std::string source = "defaults";

  /// Throws InputError naming `source` and the bad field.
  void validate() const;
};

/// Applies the keys present in a camera YAML file (width, height, fx, fy, cx, cy, depth_scale,
/// depth_invalid); absent keys keep their value. Throws InputError naming the file and the key, or
/// when the file is over kMaxCameraFileBytes (1 MiB).
void applyCameraYaml(const std::string& path, CameraModel* model);
/// The same from the file's text; `name` (a path) prefixes error messages.
void applyCameraYamlText(const std::string& text, const std::string& name, CameraModel* model);

/// Reads a 7-Scenes `camera-intrinsics.txt` (3x3 K, row-major) into fx, fy, cx, cy.
/// Throws InputError naming the file (also when it is over kMaxCameraFileBytes).
void applyIntrinsicsMatrixFile(const std::string& path, CameraModel* model);
/// The same from a stream; `name` (a path) prefixes error messages.
void applyIntrinsicsMatrix(std::istream& in, const std::string& name, CameraModel* model);

/// Applies, in order, `<folder>/camera.yaml` if present, options.camera_file, options.intrinsics
/// and options.depth_scale to `defaults`, then validates. Throws InputError naming the source.
CameraModel resolveCameraModel(const std::string& folder, const DatasetOptions& options,
                               CameraModel defaults);

}  // namespace strata

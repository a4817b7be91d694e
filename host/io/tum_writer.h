#pragma once
// Writes frames as a TUM RGB-D folder (for tests, the simulator and exporting).
#include <string>
#include <vector>

#include "core/types.h"

namespace strata {

/// Creates `dir` (and depth/, rgb/) and writes depth/NNNNNN.png (16-bit, round(depth_m *
/// depth_scale)), rgb/NNNNNN.png for frames with colour, depth.txt, rgb.txt, groundtruth.txt (each
/// frame's timestamp_s, which must increase strictly) and camera.yaml (intrinsics, depth_scale,
/// depth_invalid: [0]). Throws InputError for bad frames (size vs intrinsics, pose, timestamps,
/// depth beyond 65535 / depth_scale) and Error when a file cannot be written.
void writeTumDataset(const std::string& dir, const CameraIntrinsics& intrinsics,
                     const std::vector<RgbdFrame>& frames, double depth_scale = 5000.0);

}  // namespace strata

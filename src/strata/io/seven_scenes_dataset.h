#pragma once
// Microsoft 7-Scenes folder reader: frame-NNNNNN.{depth.png,pose.txt,color.jpg}.
#include <istream>
#include <memory>
#include <string>

#include "strata/io/open_dataset.h"

namespace strata {

/// Depth in millimetres (0 and 65535 invalid), 4x4 camera-to-world pose text per frame, timestamps
/// index / 30 s. Intrinsics: camera.yaml if present, else camera-intrinsics.txt (3x3 K), else the
/// 7-Scenes defaults fx=fy=585, cx=320, cy=240, 640x480. Frames are the frame-*.depth.png files in
/// name order. Throws InputError naming the file: no depth images, a depth image without its pose
/// file, or options.trajectory_file set (not supported for this layout).
std::unique_ptr<Dataset> open7ScenesDataset(const std::string& folder,
                                            const DatasetOptions& options);

/// True when `folder` holds at least one frame-*.depth.png.
bool looksLike7Scenes(const std::string& folder);

/// Reads a 4x4 row-major matrix text file as a pose. Throws InputError naming the file when it is
/// missing, over kMaxPoseFileBytes (64 KiB), has fewer than 16 numbers or a non-finite one, or its
/// last row is not 0 0 0 1. The rotation is replaced by the nearest rotation matrix (7-Scenes ones
/// are orthonormal to ~2e-4).
Eigen::Isometry3d readPoseMatrixFile(const std::string& path);
/// The same from a stream; `name` (a path) prefixes error messages.
Eigen::Isometry3d readPoseMatrix(std::istream& in, const std::string& name);

}  // namespace strata

#pragma once
// Writes frames as a TUM RGB-D folder (for tests, the simulator and exporting).
#include <string>
#include <vector>

#include "strata/core/types.h"
#include "strata/io/tum_format.h"

namespace strata {

/// Creates `dir` (and depth/, rgb/) and writes depth/NNNNNN.png (16-bit, round(depth_m *
/// depth_scale)), rgb/NNNNNN.png for frames with colour, depth.txt, rgb.txt, groundtruth.txt (each
/// frame's timestamp_s, which must increase strictly) and camera.yaml (intrinsics, depth_scale,
/// depth_invalid: [0]). Throws InputError for bad frames (size vs intrinsics, pose, timestamps,
/// depth beyond 65535 / depth_scale) and Error when a file cannot be written.
void writeTumDataset(const std::string& dir, const CameraIntrinsics& intrinsics,
                     const std::vector<RgbdFrame>& frames, double depth_scale = 5000.0);

/// Writes a trajectory file (`timestamp tx ty tz qx qy qz qw`, `timestamp_decimals` decimals of
/// seconds: 6 for TUM's microseconds, 9 for EuRoC's nanoseconds) atomically, after the `comment`
/// lines, each written as "# line". InputError for decimals outside 0..9; Error when it cannot be
/// written.
void writeTumTrajectory(const std::string& path, const std::vector<tum::TimedPose>& poses,
                        const std::vector<std::string>& comment, int timestamp_decimals = 6);

/// Writes a file list (rgb.txt / depth.txt: `timestamp file`) atomically, after the `comment`
/// lines. Throws InputError for a file name with whitespace (the format splits lines on it).
void writeTumFileList(const std::string& path, const std::vector<tum::TimedFile>& files,
                      const std::vector<std::string>& comment);

/// writeTumDataset's layout written one frame at a time (long recordings need not fit in
/// memory). Images are written as they come; the lists and camera.yaml atomically by finish().
class TumWriter {
 public:
  TumWriter(const std::string& dir, const CameraIntrinsics& intrinsics,
            double depth_scale = 5000.0);
  /// Validates and writes one frame; its T_W_C goes to groundtruth.txt.
  void add(const RgbdFrame& frame);
  /// Writes depth.txt, rgb.txt, groundtruth.txt and camera.yaml.
  void finish();
  std::size_t frameCount() const { return count_; }

 private:
  std::string dir_;
  CameraIntrinsics intrinsics_;
  double depth_scale_;
  std::size_t count_ = 0;
  double last_timestamp_s_ = 0.0;
  std::string depth_list_, rgb_list_, poses_;
};

}  // namespace strata

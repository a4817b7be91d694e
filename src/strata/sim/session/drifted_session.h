#pragma once
// A real recording turned into a drifting session in a frame of its own, for alignment tests: a
// slice of a TUM RGB-D folder written as a new TUM folder whose odometry.txt is the slice's truth
// with odometry drift (sim/sensors/odometry_drift.h), expressed in a random gravity-aligned
// odometry frame (sim/sensors/odometry_frame.h). Images are listed, not copied.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "strata/sim/sensors/odometry_drift.h"
#include "strata/sim/sensors/odometry_frame.h"

namespace strata::sim {

struct DriftedSessionConfig {
  /// The slice, as indices into the source's depth.txt frames in time order, both inclusive.
  std::size_t first_frame = 0;
  /// nullopt: up to the last frame.
  std::optional<std::size_t> last_frame;
  /// Seeds the drift and the odometry frame (each from its own stream).
  std::uint64_t seed = 1;
  DriftConfig drift;
  /// false: the odometry stays in the source's world frame (T_W_S = identity).
  bool offset = true;
  OdometryFrameConfig frame;

  /// Throws InputError naming the first bad field.
  void validate() const;
};

struct DriftedSession {
  std::size_t frames = 0;          // depth frames written (slice frames with a pose)
  std::size_t frames_dropped = 0;  // slice frames without a groundtruth pose within 20 ms
  Eigen::Isometry3d T_W_S = Eigen::Isometry3d::Identity();
};

/// Writes `out_dir` (created) as a TUM RGB-D folder from the slice of `source_dir` (a TUM folder:
/// depth.txt, groundtruth.txt, optional rgb.txt and camera.yaml):
/// - depth.txt, rgb.txt: the slice's images by absolute path (rgb: the image nearest each depth
///   frame within 20 ms, as the reader associates them);
/// - groundtruth.txt: the truth T_W_C at each depth frame's timestamp;
/// - odometry.txt: T_S_C = T_S_W * drifted T_W_C (first pose: T_S_W * T_W_C exactly);
/// - odometry_frame.txt: T_W_S (io/odometry_frame_file.h);
/// - camera.yaml: copied when the source has one.
/// Depth frames without a pose within 20 ms are left out and counted. Every file is written
/// atomically. Throws InputError naming the problem: a missing source folder or list, a malformed
/// list, first > last, a slice beyond the frames or without a pose, an image path with whitespace.
DriftedSession writeDriftedSession(const std::string& source_dir, const std::string& out_dir,
                                   const DriftedSessionConfig& config);

}  // namespace strata::sim

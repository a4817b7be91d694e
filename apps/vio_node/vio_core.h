#pragma once
// strata-vio's work without LCM: decoded stereo frames and IMU samples go into the VIO pipeline
// (odometry/pipeline/vio_pipeline.h), tracked frames come out as the poses to publish: T_W_C of
// cam0 at the frame's own stamp. Stamps are LCM utimes (microseconds) on whatever clock the
// stereo and IMU streams share (a replay's "now + offset" as well as a recording's own); the
// pipeline sees them as nanoseconds (utime * 1000), so a pose's utime is its frame's exactly.
// What the pipeline skips (IMU or frames not after the previous, NaN IMU, frames whose IMU never
// came) is counted in stats(); an image it refuses (wrong size or type, a missing eye) throws.
// Thread safety: not thread safe (strata-vio's worker thread only).
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "strata/io/euroc_types.h"
#include "strata/lcm/convert_stereo.h"
#include "strata/odometry/pipeline/vio_pipeline.h"

namespace strata::apps {

/// One pose to publish: T_W_C of the left camera (W: z up, see vio_pipeline.h) at `utime`.
struct VioPose {
  std::int64_t utime = 0;
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
};

class VioCore {
 public:
  /// Throws InputError for a calibration or config the pipeline cannot use.
  VioCore(const euroc::Calibration& calibration, odometry::VioPipelineConfig config);

  /// Pushes a frame; returns the poses of the frames it completed (this one once its IMU is
  /// there). Throws InputError for images the calibration does not describe (nothing changed).
  std::vector<VioPose> onFrame(const lcm_io::StereoFrameMsg& frame);
  /// Pushes an IMU sample; returns the poses of the waiting frames it completed.
  std::vector<VioPose> onImu(const lcm_io::ImuMsg& sample);
  /// End of input: frames still waiting for IMU are dropped (counted in stats()).
  void flush() { pipeline_.flush(); }

  const odometry::PipelineStats& stats() const { return pipeline_.stats(); }
  bool stereo() const { return pipeline_.stereo(); }
  /// The reason of the last failure ("" before one), and what initialisation waited for last.
  const std::string& lastFailure() const { return last_failure_; }
  const std::string& initialisingReason() const { return initialising_reason_; }

 private:
  std::vector<VioPose> collect(std::vector<odometry::PipelineFrame> frames);

  odometry::VioPipeline pipeline_;
  std::string last_failure_;
  std::string initialising_reason_;
};

}  // namespace strata::apps

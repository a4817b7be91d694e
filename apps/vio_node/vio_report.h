#pragma once
// What strata-vio tells about its run: the counters of every kind of input it took or skipped,
// the pipeline's own counts, as a one-line progress report (stderr) and as a JSON summary.
#include <cstdint>
#include <string>

#include "strata/odometry/pipeline/vio_pipeline.h"

namespace strata::apps {

/// Messages counted by kind. Frames: received = processed by the pipeline + skipped by one of
/// the kinds here or in PipelineStats (out of order, without IMU) + still queued.
struct VioCounters {
  std::int64_t frames_received = 0;         // messages on the stereo channel
  std::int64_t imu_received = 0;            // messages on the IMU channel
  std::int64_t frames_corrupt = 0;          // undecodable payload, or stereo_image_t checks refused
  std::int64_t frames_bad_image = 0;        // images the calibration does not describe (size, eye)
  std::int64_t frames_dropped_backlog = 0;  // the VIO fell behind: oldest waiting frame dropped
  std::int64_t imu_corrupt = 0;             // undecodable payload or stamp out of range
  std::int64_t imu_nonfinite = 0;           // NaN/inf values
  std::int64_t imu_dropped_backlog = 0;
  std::int64_t poses_published = 0;
  std::int64_t poses_unpublished = 0;  // LCM refused to send
};

/// The state of a run at one moment.
struct VioSnapshot {
  VioCounters counters;
  odometry::PipelineStats pipeline;
  bool stereo = true;
  std::string last_failure;         // reason of the last failure, "" before one
  std::string initialising_reason;  // what initialisation waited for last
  double elapsed_s = 0.0;           // since the node started
  std::string stopped_by;           // "signal" or "idle" once stopped, else ""
};

/// One line: frames in, tracked, initialising, failures (with the last reason), skipped by kind,
/// IMU in and skipped, and `frames_per_s` (measured by the caller over its own period).
std::string vioStatusLine(const VioSnapshot& s, double frames_per_s);

/// The verdict on a stopped run: 0, or 3 when frames were processed and none was tracked (no
/// trajectory came out: absurd IMU, no texture, a wrong calibration). `message` gets the lines to
/// print ("" when none): that one, and a warning when IMU samples no IMU could give were skipped.
int vioVerdict(const VioSnapshot& s, std::string* message);

/// The summary as JSON text (ends with a newline).
std::string vioSummaryJson(const VioSnapshot& s, const std::string& calibration_dir);

}  // namespace strata::apps

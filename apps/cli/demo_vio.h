#pragma once
// `strata demo --vio`: each simulated session fused on poses from visual-inertial odometry
// instead of the given ones. The session's grey stereo camera + IMU is rendered in memory
// (sim/session/stereo_recording.h), replayed through the VIO pipeline
// (odometry/pipeline/vio_replay.h) anchored at the true body pose where tracking starts (the
// sessions then share the truth's world frame), and the left camera's poses, interpolated at the
// RGB-D frames' times (cam0 is the RGB-D camera, both on trajectory time), replace the session's
// given poses. RGB-D frames before the VIO tracks, in a tracking gap or after its last tracked
// frame get no pose and are not fused (counted).
#include <cstddef>

#include "strata/core/progress.h"
#include "strata/sim/session/sim_session.h"

namespace strata::apps {

struct DemoVioOptions {
  bool enabled = false;
  /// Grey stereo camera resolution (focal length 0.61 * width): smaller renders faster and
  /// tracks less precisely.
  int width_px = 752;
  int height_px = 480;
  /// Keyframes in the VIO's sliding window.
  int window = 10;

  /// Throws InputError naming the bad field.
  void validate() const;
};

struct VioSessionResult {
  std::size_t stereo_frames = 0;            // grey stereo frames recorded (20 Hz) and replayed
  std::size_t tracked = 0;                  // of them, tracked
  std::size_t failures = 0;                 // tracking lost (the VIO re-initialises)
  double first_tracking_s = -1.0;           // trajectory time of the first tracked frame; -1: never
  std::size_t rgbd_frames = 0;              // the session's RGB-D frames
  std::size_t skipped_before_tracking = 0;  // of them, before the first tracked frame,
  std::size_t skipped_in_gaps = 0;          // in a tracking gap,
  std::size_t skipped_after_tracking = 0;   // after the last tracked frame
  /// The fused poses against the true ones of the same frames, without alignment (the VIO is
  /// anchored in the truth's frame, so this is the error the map sees): position RMSE and
  /// maximum, metres; orientation RMS angle, degrees.
  double ate_rmse_m = 0.0;
  double ate_max_m = 0.0;
  double rotation_rmse_deg = 0.0;
  double render_s = 0.0;  // rendering the grey frames
  double vio_s = 0.0;     // the pipeline (front end + back end), wall time

  std::size_t skipped() const {
    return skipped_before_tracking + skipped_in_gaps + skipped_after_tracking;
  }
  std::size_t fused() const { return rgbd_frames - skipped(); }
};

/// Grey stereo frames useVioPoses renders for `session` (for progress bars).
std::size_t vioFrameCount(const sim::SimSessionDataset& session, const DemoVioOptions& options);

/// Records `session`'s grey stereo + IMU (with noise unless `noise` is false), runs the VIO over
/// it and replaces the session's given poses with the VIO's (see above). `progress` counts stereo
/// frames (`done` carries the count across sessions). Throws Error when the VIO tracks none of
/// the session's RGB-D frames, naming why.
VioSessionResult useVioPoses(sim::SimSessionDataset& session, const DemoVioOptions& options,
                             bool noise, ProgressBar& progress, std::size_t& done);

}  // namespace strata::apps

#pragma once
// Options of strata-vio (the LCM visual-inertial odometry process): where it listens, which
// calibration it uses, what it publishes, when it reports and when it stops.
#include <cstddef>
#include <string>

#include "strata/lcm/channels.h"
#include "strata/odometry/pipeline/vio_pipeline.h"

namespace CLI {
class App;
}

namespace strata::apps {

struct VioChannels {
  std::string stereo = lcm_io::kStereoChannel;  // stereo_image_t in
  std::string imu = lcm_io::kImuChannel;        // imu_t in
  std::string pose = lcm_io::kPoseChannel;      // pose_t T_W_C of cam0 out
};

struct VioOptions {
  /// LCM URL to listen on; output_url "" publishes on the same.
  std::string url = lcm_io::kDefaultUrl;
  std::string output_url;
  VioChannels channels;
  /// EuRoC session folder (or its mav0/): only the cam0, cam1 and imu0 sensor.yaml files are read.
  std::string calib_dir;
  /// The VIO's settings (odometry/pipeline/vio_pipeline.h): its defaults; --mono sets
  /// pipeline.mono (left camera only, scale from the IMU, even when cam1 is calibrated).
  odometry::VioPipelineConfig pipeline;
  /// Frames waiting for the VIO (receive -> worker); beyond it the oldest frame is dropped
  /// (counted). IMU samples are never dropped for frames: the preintegration needs every one.
  std::size_t queue_frames = 8;
  /// Exit once no stereo or IMU message came for this long, seconds (also before the first one);
  /// 0: run until SIGINT/SIGTERM.
  double max_idle_s = 0.0;
  /// One progress line on stderr this often, seconds; 0: none.
  double status_period_s = 5.0;
  /// JSON summary written atomically at exit; "": none.
  std::string summary_path;
  bool quiet = false;
  bool solver_log = false;  // the solver's own log on stderr (odometry/solver_log.h)

  /// Throws InputError naming the bad option.
  void validate() const;
};

/// Registers strata-vio's options on `app`.
void addVioOptions(CLI::App& app, VioOptions& options);

}  // namespace strata::apps

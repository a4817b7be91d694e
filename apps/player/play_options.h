#pragma once
// Options of strata-play: what to replay, how fast, and how it is sent.
#include <string>

#include "strata/lcm/channels.h"
#include "strata/lcm/convert_frame.h"

namespace CLI {
class App;
}

namespace strata::apps {

struct PlayOptions {
  /// A TUM RGB-D folder, an EuRoC/ASL session folder (mav0/: grey stereo + IMU, see
  /// player/play_euroc.h), or "sim:WORLD[:SESSION]" (a shipped world name or a world YAML path).
  std::string dataset;
  std::string url = lcm_io::kDefaultUrl;
  std::string rgbd_channel = lcm_io::kRgbdChannel;
  std::string camera_info_channel = lcm_io::kCameraInfoChannel;
  std::string pose_channel = lcm_io::kPoseChannel;
  std::string imu_channel = lcm_io::kImuChannel;
  std::string stereo_channel = lcm_io::kStereoChannel;
  std::string command_channel = lcm_io::kCommandChannel;
  std::string stats_channel = lcm_io::kStatsChannel;
  std::string camera_id = "depth";
  /// Speed relative to the recording (1 = real time); 0 = as fast as the mapper fuses (flow
  /// control by its map_stats_t: at most `window` frames unaccounted for).
  double rate = 1.0;
  int window = 2;
  int first = 0;   // index of the first frame sent (a replay resumed where it stopped)
  int frames = 0;  // 0: all
  int stride = 1;
  /// Synthetic sessions: frames kept along the trajectory (0: every frame at 30 Hz).
  int sim_frames = 60;
  bool sim_noise = true;
  /// Poses on the pose channel (the mapper interpolates) instead of inside each frame.
  bool separate_poses = false;
  /// Synthetic sessions: IMU samples between frames on the IMU channel.
  bool imu = false;
  /// false (--no-poses): frames go without a pose and nothing is sent on the pose channel; a pose
  /// source on that channel (strata-vio) provides them.
  bool poses = true;
  /// A `strata sim --stereo` session folder: its mav0/ grey stereo + IMU are sent too, between
  /// the RGB-D frames in time order on their clock (player/play_with_stereo.h). Needs rate > 0.
  bool with_stereo = false;
  lcm_io::FrameEncoding encoding;
  /// Stamps = now + the recording's offsets (a replay is newer than what the mapper has seen);
  /// false keeps the recording's own stamps.
  bool restamp = true;
  /// After the last frame: end the mapper's session (change events), optionally save its map.
  bool end_session = true;
  std::string save_path;
  /// How long to wait for the mapper's stats (flow control, command replies), seconds.
  double mapper_timeout_s = 30.0;
  bool quiet = false;

  /// Throws InputError naming the bad option.
  void validate() const;
};

void addPlayOptions(CLI::App& app, PlayOptions& options);

}  // namespace strata::apps

#pragma once
// `strata sim [WORLD] --sessions N --out DIR`: render every session of a world to disk in the TUM
// RGB-D layout, with the ground truth (meshes, object poses, changes) and IMU in the EuRoC layout;
// with --stereo also a grey stereo camera + IMU + body ground truth in the EuRoC/ASL layout (mav0/,
// sim/session/stereo_recording.h).
// The options are checked before the world file is read, and --out (a writable folder or a new
// one in a writable folder, not the world file) before anything is written; a run that fails
// while writing removes what it made (a new --out, or its new ground_truth/ and session folders).
// Exit 0 on success, 2 on bad input (named), 1 on other errors.
#include <cstdint>
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct SimOptions {
  std::string world;  // "" = the shipped single room
  int sessions = 0;   // 0 = the world file's count
  std::string out_dir = "strata_sim";
  std::uint64_t seed = 0;  // 0 = the world file's seed
  int max_frames = 0;      // per session, 0 = every frame at --rate
  double rate_hz = 30.0;
  bool no_noise = false;
  bool drift = false;
  /// Odometry in a random gravity-aligned frame per session (T_S_C), the true T_W_S beside it in
  /// odometry_frame.txt. Implies drift: an odometry's own frame comes with its drift.
  bool own_frames = false;
  /// The RGB camera sees the grey camera's world-anchored texture (sensors/rgbd_camera.h).
  bool color_texture = false;
  bool quiet = false;
  /// > 0: each session's camera rests this long before the path starts (a VIO standstill start;
  /// every stream, RGB-D included, covers the rest).
  double rest_s = 0.0;
  /// EuRoC layout per session (mav0/): grey stereo at 20 Hz, IMU at 200 Hz, body ground truth.
  bool stereo = false;
  bool mono = false;               // with stereo: cam0 only
  double stereo_duration_s = 0.0;  // > 0: only the first seconds of each path
  int stereo_width_px = 752;
  int stereo_height_px = 480;
  double exposure_gain_sigma = 0.03;
  double exposure_offset_sigma = 2.0;
};

CLI::App* addSimCommand(CLI::App& app, SimOptions& options);
int runSim(const SimOptions& options);

}  // namespace strata::apps

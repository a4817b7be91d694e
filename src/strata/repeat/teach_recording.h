#pragma once
// The teach run: a route (taught_route.h) flown in one session of a simulated world, recorded
// as a TUM RGB-D session folder exactly as `strata sim` writes one (depth/, rgb/, depth.txt,
// rgb.txt, camera.yaml, groundtruth.txt = the truth), with simulated visual-inertial odometry
// (odometry.txt: the truth with sim::addOdometryDrift's random walk, first pose exact) and
// imported into <dir>/map.sqlite (store::importTumSession, odometry from odometry.txt): the map
// frame is the teach's odometry frame and the map holds no true pose. taught_path.txt is the
// path as the map believes it (the odometry poses, TUM format).
// Frames: world W (z up) = the odometry frame at the first pose; camera C (x right, y down,
// z forward). Metres, radians, seconds.
// Errors: InputError for bad settings or a route that cannot be flown; Error when a file cannot
// be written. Files are written atomically (images as they come).
// Thread safety: functions only.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "strata/io/tum_format.h"
#include "strata/repeat/taught_route.h"
#include "strata/sim/sensors/odometry_drift.h"
#include "strata/sim/sensors/rgbd_camera.h"
#include "strata/store/session_import.h"

namespace strata::repeat {

/// The robot's RGB-D camera, the same for teach and repeat (the localiser matches its images
/// against the teach's keyframes): horizontal, along the robot's yaw.
struct CameraSetup {
  int width_px = 320;
  int height_px = 240;
  /// Horizontal field of view (radians): 1.2 rad = 69 degrees.
  double horizontal_fov_rad = 1.2;
  double min_range_m = 0.3;
  double max_range_m = 5.0;
  /// Colour with the world-anchored texture (corners for ORB, as real surfaces have); false:
  /// flat-shaded colour (the localiser then relies on its surface path).
  bool texture = true;
  /// The texture's contrast (sim::WorldTextureConfig::contrast; its default 0.6 leaves cells
  /// on the dark walls 20-30 grey levels apart, about FAST's threshold: a teach frame then
  /// localised against its own map 55-69 % of the time, at 0.95 93 %) and the size of its
  /// cells relative to the default (8 and 2.3 cm; 1 measured best at 320 x 240).
  double texture_contrast = 0.95;
  double texture_scale = 1.0;

  sim::RgbdCameraConfig config() const;
  void validate() const;
};

struct TeachConfig {
  RouteConfig route;
  CameraSetup camera;
  double camera_rate_hz = 5.0;
  /// The teach's VIO drift: 2.5 cm/sqrt(m) and 0.01 rad/sqrt(m) is 1-2 % of the distance over
  /// 50 m.
  sim::DriftConfig drift = defaultDrift();
  /// The world session flown (its objects and lighting).
  int session = 0;
  /// Seeds the depth noise and the drift.
  std::uint64_t seed = 1;
  /// A map keyframe every this many frames (0.4 m apart at 0.8 m/s and 5 Hz).
  int keyframe_every = 3;

  static sim::DriftConfig defaultDrift();
  /// InputError naming the bad field.
  void validate() const;
};

struct TeachResult {
  std::vector<Eigen::Vector3f> waypoints_W;
  std::vector<tum::TimedPose> truth;     // camera poses of the frames (world)
  std::vector<tum::TimedPose> odometry;  // the same frames as the odometry saw them (map frame)
  double length_m = 0.0;                 // flown (truth)
  double duration_s = 0.0;               // simulated
  double final_drift_m = 0.0, max_drift_m = 0.0;  // |odometry - truth| of the camera centres
  store::ImportResult import;
};

/// done of total frames rendered.
using TeachProgress = std::function<void(std::size_t done, std::size_t total)>;

/// Flies, renders and writes the teach folder `dir` (created; its files replaced) and imports
/// it into dir/map.sqlite. The folder must stay where it is: the map reads its images.
TeachResult recordTeach(const sim::World& world, const TeachConfig& config, const std::string& dir,
                        const TeachProgress& progress = {});

/// The lighting of a world session, as its cameras render it.
sim::Lighting sessionLighting(const sim::World& world, int session);

/// The files recordTeach writes into its folder (besides depth/ and rgb/).
inline constexpr const char* kTaughtPathFile = "taught_path.txt";
inline constexpr const char* kMapFile = "map.sqlite";

}  // namespace strata::repeat

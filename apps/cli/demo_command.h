#pragma once
// `strata demo` (and `strata` with no command): the multi-session demo on a synthetic world:
// simulate every session, fuse each into its own layer of a ChangeDetector on the device, discover
// the objects that moved, score them and the static map against the world's ground truth, and
// write meshes, label overlays and a report. With --vio the sessions are fused on poses from
// visual-inertial odometry over their simulated grey stereo + IMU.
#include <cstdint>
#include <string>

#include "cli/demo_vio.h"
#include "cli/select_incremental.h"

namespace CLI {
class App;
}

namespace strata::apps {

struct DemoOptions {
  std::string world;  // "" = the shipped single room
  int sessions = 0;   // 0 = the world's count
  std::string out_dir = "strata_out";
  std::uint64_t seed = 0;
  int frames = 60;  // per session, spread over the path
  float voxel_size_m = 0.02f;
  /// Frames a voxel must be seen in to count as observed (change detection's minimum weight; the
  /// demo fuses with constant weights). 60 frames spread over a session see most surfaces 3+
  /// times; 10 suits full-rate recordings.
  float min_weight = 3.0f;
  bool no_noise = false;
  std::string device;
  bool quiet = false;
  /// Also run keyframe selection's incremental loop: about doubles the demo's time.
  bool incremental = false;
  /// Its moving-average window and dilation, keyframes (selection::demoLoopConfig's 1 and 0, the
  /// demo's keyframes being 2.8 s apart; the method's 5 and 1 suit overlapping keyframes).
  IncrementalOptions select;
  /// Fuse every session on poses from visual-inertial odometry (cli/demo_vio.h).
  DemoVioOptions vio;
  /// Sessions in drifting frames of their own, registered by multi-session alignment
  /// (cli/demo_align.h) and fused on the aligned poses.
  bool align = false;
  /// Teach and repeat without truth poses (cli/demo_localize.h): session 0's drifting odometry
  /// is the map, every later session is localised against it and fused on its fused poses.
  bool localize = false;
  /// Seconds the camera stands still before each path (the VIO's standstill start); < 0: 1.5 with
  /// vio, 0 without.
  double rest_s = -1.0;
  /// Build the object database over the sessions as the last step (cli/demo_objects.h).
  bool objects = true;
  double restSeconds() const { return rest_s >= 0.0 ? rest_s : (vio.enabled ? 1.5 : 0.0); }
};

struct DemoReport;

CLI::App* addDemoCommand(CLI::App& app, DemoOptions& options);
/// Prints the summary; returns the exit code (0 done, 2 bad input, 3 device error, 1 other).
int runDemo(const DemoOptions& options);
/// The work of runDemo (files written, nothing printed but progress), returning what it measured.
/// Throws on failure.
DemoReport runDemoPipeline(const DemoOptions& options);

}  // namespace strata::apps

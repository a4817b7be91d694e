#pragma once
// `strata teach WORLD.yaml --out DIR [--session N] [--seed N] [--length M] [--width PX]
// [--height PX] [--flat]`: the teach of teach and repeat (repeat/teach_recording.h): a route of
// at least --length metres flown through one session of a simulated world, recorded into DIR as a
// TUM RGB-D session folder as `strata sim` writes one (groundtruth.txt = truth, odometry.txt =
// drifted odometry), imported into DIR/map.sqlite (map frame = the teach's odometry), with
// DIR/taught_path.txt (the path as the map believes it), DIR/teach.json (the world and the
// settings, which `strata repeat` checks) and DIR/teach.png (from above). Progress on stderr.
// Options are checked before the world file is read; a failed run leaves none of its files.
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct TeachOptions {
  std::string world_path;
  std::string out_dir;
  int session = 0;
  unsigned long long seed = 1;
  double length_m = 50.0;
  int width_px = 320;
  int height_px = 240;
  bool flat = false;  // flat-shaded colour instead of the world texture
  bool quiet = false;
};

CLI::App* addTeachCommand(CLI::App& app, TeachOptions& options);
/// Returns the exit code: 0 ok, 1 error, 2 bad input (naming the problem).
int runTeach(const TeachOptions& options);

/// The file in a teach folder that names its world (and the teach's settings).
inline constexpr const char* kTeachJson = "teach.json";

}  // namespace strata::apps

#pragma once
// `strata repeat WORLD.yaml --taught DIR --session K --out OUT [--no-localization] [--compare]
// [--map] [--seed N] [--localize-every N]`: the repeat of teach and repeat
// (repeat/repeat_loop.h): the path taught in DIR (`strata teach`) flown again in session K of the
// same world, its estimate the odometry fused with localisations against DIR/map.sqlite (with
// --no-localization the odometry alone; --compare runs both). Writes OUT/report.json (following
// error against the taught truth, drift, localisations, stops, collisions), OUT/repeat.png (from
// above: taught path, flown path and estimate, true positions), OUT/<mode>_trajectory.csv and,
// with --map, the live map (OUT/<mode>_map.strata). Progress on stderr.
// A --taught folder without map.sqlite or teach.json, or taught in another world, is refused
// before anything is written; a failed run leaves none of its files.
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct RepeatOptions {
  std::string world_path;
  std::string taught_dir;
  int session = 1;
  std::string out_dir;
  bool no_localization = false;
  bool compare = false;
  bool save_map = false;
  bool no_checks = false;  // no live map, no checks of the path ahead: the taught path flown blind
  unsigned long long seed = 2;
  int localize_every = 2;
  std::string device;
  bool quiet = false;
};

CLI::App* addRepeatCommand(CLI::App& app, RepeatOptions& options);
/// Returns the exit code: 0 ok (also when the run stopped before the end: the report says why),
/// 1 error, 2 bad input (naming the problem), 3 device error.
int runRepeatCommand(const RepeatOptions& options);

}  // namespace strata::apps

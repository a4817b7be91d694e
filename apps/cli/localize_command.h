#pragma once
// `strata localize SESSION_DIR --db MAP.sqlite --out trajectory.txt`: every frame of a recorded
// session (TUM layout) localised against a prior map built by `strata map import` / `strata
// align` (src/strata/localize, docs/localize.md). The session's odometry (odometry.txt, or
// --odometry FILE; never its groundtruth.txt) is fused with the localisations when present;
// without it each frame is localised on its own. Writes the map-frame poses of the frames it
// could place (TUM, camera-to-map) and a JSON summary (--summary, default: the trajectory's path
// with .json): localised fraction, per-frame status and reason, timings and, with --truth FILE
// (TUM, in the map's frame), the error of every placed frame.
// The map database is only read. Options and paths are checked before anything is read; a map
// that does not show the session's place (a sample of frames localises nowhere) is refused.
// Exit 0 done, 2 bad input (named), 1 other failures; a failed run leaves no output behind.
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct LocalizeOptions {
  std::string session_dir;
  std::string db_path;
  std::string out_path;
  std::string summary_path;   // default: out_path with .json
  std::string odometry_path;  // default: SESSION_DIR/odometry.txt when present
  bool no_odometry = false;
  std::string truth_path;     // optional: score the placed frames
  int every = 1;
  int threads = 2;
  bool quiet = false;
};

CLI::App* addLocalizeCommand(CLI::App& app, LocalizeOptions& options);
int runLocalize(const LocalizeOptions& options);

}  // namespace strata::apps

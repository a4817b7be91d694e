#pragma once
// `strata objects SESSION_DIR... --out DIR`: the incremental object database over sessions.
// Every session (a TUM RGB-D folder, e.g. from `strata sim`) is fused with change detection as
// `strata diff` does; the objects that moved are matched, merged into object models or found new
// ones (objects/object_database.h), and the files of cli/objects_outputs.h are written. Session
// folders from `strata sim` bring their ground truth: the database is then scored against it
// (eval/object_db_eval.h) under "truth" in objects.json. Options and paths (--out, its files and
// --before-after against the sessions and --world) are checked before any session is read; --out
// is made only with the results, and a failed write leaves none of them.
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace strata::apps {

struct ObjectsOptions {
  std::vector<std::string> sessions;  // folders, in time order
  std::string out_dir;
  float voxel_size_m = 0.02f;
  /// Frames per session, spread evenly over it (every k-th frame); 0: all.
  int frames = 0;
  /// Frames (of the full recording) a voxel must be seen in to count as observed; divided by the
  /// stride --frames implies (as `strata diff --stride`).
  float min_weight = 10.0f;
  /// The world of the sessions' ground truth when it is not a shipped one ("" = its name).
  std::string world;
  std::string device;
  bool quiet = false;
  /// Also write the before / after picture (objects_before_after.h) here ("" = none).
  std::string before_after_png;
};

CLI::App* addObjectsCommand(CLI::App& app, ObjectsOptions& options);

/// Returns the exit code: 0 done, 2 bad input (a missing session names its path; fewer than two
/// sessions; no --out), 3 device error, 1 anything else.
int runObjects(const ObjectsOptions& options);

}  // namespace strata::apps

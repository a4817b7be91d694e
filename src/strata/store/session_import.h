#pragma once
// Import of a recorded session folder (TUM RGB-D layout, as `strata sim` writes) into a map
// database, and export of a map's trajectories back to TUM files.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "strata/store/session_store.h"

namespace strata::store {

struct ImportOptions {
  /// A keyframe every N frames (0: off). With keyframe_distance_m as well, either one starts a
  /// keyframe; at least one must be on. The first frame is always a keyframe.
  int keyframe_every = 10;
  /// A keyframe once the camera moved this far from the last keyframe, metres (0: off).
  double keyframe_distance_m = 0.0;
  /// Odometry edges get the information diag(1/sigma_m^2 x3, 1/sigma_rad^2 x3): the drift of
  /// visual-inertial odometry between keyframes a few frames apart is of this order (1 cm,
  /// 0.01 rad ~ 0.6 deg); a later stage that knows better rewrites them.
  double odometry_sigma_m = 0.01;
  double odometry_sigma_rad = 0.01;
  /// Record each keyframe's depth and colour image as a resource (referenced, with CRC-32).
  bool attach_images = true;
};

struct ImportResult {
  bool skipped = false;  // the folder was already in the map; nothing written
  std::int64_t session_id = 0;
  std::string name;
  std::string odometry_file;  // odometry.txt, or groundtruth.txt when there is none
  std::size_t frames = 0, keyframes = 0, edges = 0, resources = 0;
};

/// done of total keyframes written.
using ImportProgress = std::function<void(std::size_t done, std::size_t total)>;

/// Imports one session folder: its odometry is odometry.txt when present, else groundtruth.txt,
/// taken as T_S_C in the session's own frame (the file's "world" is the session frame S). Frames
/// are depth.txt's entries that have an odometry pose within 20 ms (tum_format.h), or every pose
/// when there is no depth.txt; a keyframe takes its pose's timestamp. Consecutive keyframes are
/// joined by odometry edges. All of it is one transaction: the session is in the map whole or
/// not at all. A folder already in the map is skipped (result.skipped). The session is named
/// after the folder. InputError for a folder without odometry, malformed files or options.
ImportResult importTumSession(Store& store, const std::string& folder, const ImportOptions& options,
                              const ImportProgress& progress = {});

/// Writes each session's keyframe trajectory as TUM files into `out_dir/<session name>/`
/// (`<name>_<id>` when two sessions share a name): odometry.txt (timestamp and T_S_C) and, when
/// any keyframe has one, optimised.txt (T_W_C of those keyframes). Files written atomically.
/// Returns the files written.
std::vector<std::string> exportTrajectories(Store& store, const std::string& out_dir);

}  // namespace strata::store

#pragma once
// `strata diff SESSION_DIR... --out DIR`: multi-session change detection. Every session
// (a TUM RGB-D / 7-Scenes folder, e.g. written by `strata sim`, or a saved .strata map) is fused
// into its own layer of a ChangeDetector, in the order given; then the static map's mesh, one PLY
// per discovered object per session, a label overlay PNG per session and report.json are written.
// Options and paths are checked before any session is read; saved maps must share one voxel grid
// (the error names both files); --out is made only with the results, and a failed write leaves
// none of them.
#include <string>
#include <vector>

#include "strata/io/open_dataset.h"

namespace CLI {
class App;
}

namespace strata::apps {

struct DiffOptions {
  std::vector<std::string> sessions;  // folders or .strata files, in time order
  /// Empty, or one TUM trajectory per session in order (e.g. aligned odometry) whose poses replace
  /// the folder's groundtruth.txt (DatasetOptions::trajectory_file); saved maps take none.
  std::vector<std::string> trajectories;
  std::string out_dir;
  float voxel_size_m = 0.02f;  // ignored when a session is a saved map (its own is used)
  /// "constant" (default: the minimum weight then counts frames) or "inv-z2".
  std::string weight = "constant";
  float min_weight = 10.0f;              // ChangeConfig::min_weight
  float difference_threshold_m = 0.05f;  // ChangeConfig::difference_threshold_m
  int frames = 0;                        // per session, 0: all
  int stride = 1;                        // every n-th frame
  std::string device;
  bool quiet = false;
  DatasetOptions dataset_options;
};

CLI::App* addDiffCommand(CLI::App& app, DiffOptions& options);

/// Returns the exit code: 0 done, 2 bad input (a missing or unreadable session names its path; as
/// many --trajectory as sessions, or none), 3 device error, 1 anything else.
int runDiff(const DiffOptions& options);

}  // namespace strata::apps

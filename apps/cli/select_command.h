#pragma once
// `strata select MAP SESSION_DIR --out DIR`: keyframe selection by raycast reprojection.
// Renders the map into every frame of the session on a sparse pixel grid (device), scores coverage,
// change and depth change (or a baseline similarity), smooths them along the trajectory, selects
// the keyframes worth reconstructing and writes keyframes.csv, selection.png (metrics, thresholds,
// selected frames) and selected.png (contact sheet of the selected images). Options and paths are
// checked before the map is read; a failed write leaves none of the files.
#include <string>

namespace CLI {
class App;
}

namespace strata::apps {

struct SelectOptions {
  std::string map_path;
  std::string session_dir;
  std::string out_dir = "strata_select";
  std::string method = "reproj";  // reproj | ncc | hist
  /// Session the map was built from: the thresholds become its extremes against the map
  /// (automatic thresholds); the explicit thresholds below are then ignored.
  std::string calibrate_dir;
  int stride_px = 10;
  int window = 5;
  int dilation = 1;
  double coverage_threshold = 0.9;
  double change_threshold = 0.25;
  double depth_threshold_m = 0.15;
  double surface_threshold = 0.02;
  double ncc_threshold = 0.5;
  double hist_threshold = 0.8;
  int frames = 0;  // 0: all
  std::string device;
  bool quiet = false;
};

CLI::App* addSelectCommand(CLI::App& app, SelectOptions& options);
/// Returns the exit code: 0 done, 2 bad input, 3 device error, 1 other.
int runSelect(const SelectOptions& options);

}  // namespace strata::apps

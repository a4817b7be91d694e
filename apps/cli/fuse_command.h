#pragma once
// `strata fuse [DATASET]`: fuse a dataset (TUM, 7-Scenes, or the built-in analytic scene) into a
// TSDF map on the device, then write the mesh, the map and a rendered view. The options (finite
// numbers in range, known modes) and every output (against the dataset folder, --camera and each
// other; each a file in a writable folder) are checked before the dataset is opened or a device
// is made. Exit 0 on success, 2 on bad input (named), 3 on a device error, 1 otherwise (a frame
// that fails part-way keeps what was fused before it: written, exit 1).
#include <string>

#include "strata/io/open_dataset.h"
#include "strata/map/map_config.h"

namespace CLI {
class App;
}

namespace strata::apps {

struct FuseOptions {
  std::string dataset;  // "" or "analytic": the built-in analytic scene
  MapConfig map;
  float truncation_m = 0.0f;  // 0: map.truncation_voxels applies
  std::string weight = "inv-z2";
  std::string distance = "point-to-plane";
  int frames = 0;             // 0: all
  int stride = 1;
  std::string mesh_path;
  std::string map_path;
  std::string render_path;    // PNG of the map rendered from the last pose
  std::string device;
  bool reference = false;     // fuse with the C++ reference instead of the device
  bool esdf = false;          // keep the ESDF up to date during fusion (device only)
  std::string esdf_png_path;  // write an ESDF slice at the end (implies esdf)
  float slice_z_m = 1.0f;     // height of that slice
  int free_space = -1;        // map.allocate_free_space: 1 on, 0 off, -1 as set (on with esdf)
  bool quiet = false;
  /// A frame that cannot be read or is refused as bad input is skipped (named, counted) instead
  /// of ending the run without output.
  bool skip_bad_frames = false;
  bool track = false;           // ignore the dataset's poses after the first: track each frame
  std::string trajectory_path;  // with track: the estimated poses, TUM format (camera to world)
  DatasetOptions dataset_options;
};

/// Registers `fuse` on `app`; the options are filled when it parses.
CLI::App* addFuseCommand(CLI::App& app, FuseOptions& options);

/// Runs the fusion; returns the process exit code. Errors print a message naming the problem.
int runFuse(FuseOptions options);

}  // namespace strata::apps

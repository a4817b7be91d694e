#pragma once
// `strata esdf MAP --slice-z 1.0 --png out.png`: load a saved map, compute its ESDF on the device
// (DeviceEsdf::updateAll), write a colour-mapped horizontal slice and print a summary. The options
// (finite --slice-z, positive finite --max-distance) and --png (a file in a writable folder, not
// the map) are checked before the map is read or a device is opened.
#include <cstddef>
#include <string>

namespace CLI {
class App;
}
namespace strata::apps {

struct EsdfOptions {
  std::string map_path;
  float slice_z_m = 1.0f;
  std::string png_path;         // "" : no picture (the slice is still summarised)
  float max_distance_m = 2.0f;  // the ESDF's maximum distance, also the colour range's top
  /// Also compute the C++ reference and report the share of observed voxels whose device
  /// distance differs by more than one voxel size (target: at most 0.2 %, mean below 0.1 voxel);
  /// exit 1 when over.
  bool voxel_size_check = false;
  std::string device;
};

/// Registers `esdf` on `app`; the options are filled when it parses.
CLI::App* addEsdfCommand(CLI::App& app, EsdfOptions& options);

/// Runs it; returns the exit code (0 ok, 1 check failed / other error, 2 bad input naming the
/// problem (bad option, --png over the map, missing or corrupt map file, no block at the slice
/// height), 3 device error).
int runEsdf(const EsdfOptions& options);

}  // namespace strata::apps

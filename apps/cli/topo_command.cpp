#include "cli/topo_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <vector>

#include "cli/option_checks.h"
#include "cli/plan_load.h"
#include "cli/run_outputs.h"
#include "cli/topo_outputs.h"
#include "strata/core/error.h"
#include "strata/plan/topo_map.h"

namespace strata::apps {
namespace {

const std::vector<std::string> kTopoFiles = {"topo.json", "topo.png"};

int runChecked(const TopoOptions& o) {
  // The options before any file is read, then the outputs against the map.
  if (o.map_path.empty()) throw InputError("a map file (.strata) is required");
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  checkRadius(o.radius_m, o.esdf_max_distance_m);
  const UnknownPolicy unknown = parseUnknownPolicy(o.unknown);
  if (std::isinf(o.slice_z_m)) {
    throw InputError("--slice-z must be a finite height in metres (or left out), not " +
                     std::string(o.slice_z_m > 0 ? "inf" : "-inf"));
  }
  checkMapOutputs(o.map_path, o.out_dir, kTopoFiles);
  const LoadedEsdf loaded = loadEsdf(o.map_path, o.esdf_max_distance_m, o.device);
  const plan::TopoMap topo(*loaded.esdf, plan::TopoOptions{o.radius_m, unknown});
  // A failed write leaves none of the files (nor the folder when this run made it).
  OutputCleanup cleanup;
  cleanup.folder(o.out_dir, kTopoFiles);
  std::filesystem::create_directories(o.out_dir);
  const std::filesystem::path dir(o.out_dir);
  writeTopoJson((dir / "topo.json").string(), topo);
  const float z_m = writeTopoPng((dir / "topo.png").string(), topo, o.slice_z_m);
  cleanup.keep();
  std::printf(
      "strata topo: %zu clusters, %zu portals, %zu edges over %zu traversable voxels (radius %.2f "
      "m), built in %.1f ms; graph %.2f MB against %.2f MB for grid A*. Picture at z = %.2f m. "
      "Wrote %s/{topo.json,topo.png}.\n",
      topo.clusters().size(), topo.portals().size(), topo.edgeCount(),
      topo.stats().traversable_voxels, o.radius_m, topo.stats().build_ms, topo.memoryBytes() / 1e6,
      gridMemoryBytes(topo) / 1e6, z_m, o.out_dir.c_str());
  return 0;
}

}  // namespace

CLI::App* addTopoCommand(CLI::App& app, TopoOptions& o) {
  CLI::App* cmd =
      app.add_subcommand("topo", "Build the topological map of a saved map's free space");
  cmd->add_option("map", o.map_path, "Map file (.strata)")->required();
  cmd->add_option("--out", o.out_dir, "Output folder")->required();
  cmd->add_option("--radius", o.radius_m, "Robot radius, metres (>= 0)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--unknown", o.unknown, "Unknown space: occupied (safe) or free")
      ->capture_default_str()
      ->check(CLI::IsMember({"occupied", "free"}));
  cmd->add_option("--esdf-max-distance", o.esdf_max_distance_m,
                  "ESDF maximum distance, metres (above the radius)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--slice-z", o.slice_z_m,
                  "Height of the picture, metres (default: the busiest layer)")
      ->check(finiteNumber());
  cmd->add_option("--device", o.device,
                  "Vulkan device index or name substring (env STRATA_DEVICE)");
  return cmd;
}

int runTopo(const TopoOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata topo: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata topo: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata topo: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps

#include "cli/topo_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "cli/plan_load.h"
#include "cli/topo_outputs.h"
#include "strata/core/error.h"
#include "strata/plan/topo_map.h"

namespace strata::apps {
namespace {

int runChecked(const TopoOptions& o) {
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  if (!std::isfinite(o.radius_m) || o.radius_m < 0.0f) {
    throw InputError("--radius must be finite and >= 0");
  }
  if (!(o.radius_m < o.esdf_max_distance_m)) {
    throw InputError("--radius must be below --esdf-max-distance (no larger sphere can be free)");
  }
  const UnknownPolicy unknown = parseUnknownPolicy(o.unknown);
  const LoadedEsdf loaded = loadEsdf(o.map_path, o.esdf_max_distance_m, o.device);
  const plan::TopoMap topo(*loaded.esdf, plan::TopoOptions{o.radius_m, unknown});
  std::filesystem::create_directories(o.out_dir);
  const std::filesystem::path dir(o.out_dir);
  writeTopoJson((dir / "topo.json").string(), topo);
  const float z_m = writeTopoPng((dir / "topo.png").string(), topo, o.slice_z_m);
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
  cmd->add_option("--radius", o.radius_m, "Robot radius, metres")->capture_default_str();
  cmd->add_option("--unknown", o.unknown, "Unknown space: occupied (safe) or free")
      ->capture_default_str();
  cmd->add_option("--esdf-max-distance", o.esdf_max_distance_m, "ESDF maximum distance, metres")
      ->capture_default_str();
  cmd->add_option("--slice-z", o.slice_z_m,
                  "Height of the picture, metres (default: the busiest layer)");
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

#include "cli/esdf_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "cli/esdf_slice.h"
#include "cli/option_checks.h"
#include "strata/core/clock.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/mapper/mapper.h"
#include "strata/io/image_io.h"
#include "strata/esdf/esdf.h"
#include "strata/esdf/esdf_compare.h"
#include "strata/map/map_file.h"

namespace strata::apps {
namespace {

using Clock = std::chrono::steady_clock;

// The ESDF's tolerance: share of voxels off by more than one voxel size, mean error in voxels.

std::size_t knownVoxels(const EsdfMap& map) {
  std::size_t known = 0;
  for (const auto& [b, block] : map.blocks) {
    for (const EsdfVoxel& v : block) known += esdfObserved(v) ? 1 : 0;
  }
  return known;
}

/// The slice part of the summary; writes the PNG when asked (then a missing layer is an error).
std::string sliceSummary(const EsdfOptions& o, const EsdfMap& esdf) {
  EsdfSliceOptions slice_options;
  slice_options.z_m = o.slice_z_m;
  slice_options.max_distance_m = o.max_distance_m;
  std::ostringstream s;
  s.precision(2);
  s << std::fixed;
  const auto start = Clock::now();
  EsdfSlice slice;
  try {
    slice = renderEsdfSlice(esdf, slice_options);
  } catch (const InputError& e) {
    if (!o.png_path.empty()) throw;
    s << " No slice: " << e.what() << ".";
    return s.str();
  }
  const EsdfSliceStats& st = slice.stats;
  s << " Slice at z = " << o.slice_z_m << " m: " << st.width_voxels << " x " << st.height_voxels
    << " voxels, " << st.known << " known, " << st.unknown << " unknown, " << st.outside
    << " in no block; distance from " << st.min_distance_m << " to " << st.max_distance_m << " m.";
  if (!o.png_path.empty()) {
    writeColorPng(o.png_path, slice.image);
    s << " Wrote " << o.png_path << " (" << slice.image.width_px << " x " << slice.image.height_px
      << " px, " << msSince(start) << " ms).";
  }
  return s.str();
}

/// The options and the output against the map, before the map is read or a device is opened
/// (the parser refuses only NaN and inf; tests call runEsdf without it).
void validate(const EsdfOptions& o) {
  if (o.map_path.empty()) throw InputError("no map file given");
  requireFiniteHeight(o.slice_z_m, "--slice-z");
  requireNumber(o.max_distance_m, "--max-distance", "metres", 0.0, false);
  OutputPaths paths;
  paths.inputFile(o.map_path, "the map");
  paths.outputFile(o.png_path, "--png");
  paths.check();
}

int runChecked(const EsdfOptions& o) {
  validate(o);
  const TsdfMap tsdf = loadMap(o.map_path);
  EsdfConfig config;
  config.max_distance_m = o.max_distance_m;
  config.validate(tsdf.config().voxel_size_m);
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  const auto context = vk::Context::create(context_options);
  MapperConfig mapper_config;
  mapper_config.map = tsdf.config();
  mapper_config.esdf = true;
  mapper_config.esdf_config = config;
  const std::unique_ptr<Mapper> mapper = Mapper::fromMap(tsdf, *context, mapper_config);
  const EsdfUpdateStats stats = mapper->updateEsdf();  // the first update: every block
  const EsdfMap& host = mapper->esdf();

  const std::size_t voxels = host.blocks.size() * kVoxelsPerBlock;
  const std::size_t known = knownVoxels(host);
  std::ostringstream s;
  s.precision(2);
  s << std::fixed << "ESDF of '" << o.map_path << "' (" << host.blocks.size() << " blocks, "
    << voxels << " voxels of " << tsdf.config().voxel_size_m << " m, "
    << (voxels > 0 ? 100.0 * known / voxels : 0.0) << " % known, max distance " << o.max_distance_m
    << " m) on " << context->deviceName() << ": " << stats.device_ms << " ms device time, "
    << stats.wall_ms << " ms wall for the full update.";
  s << sliceSummary(o, host);
  bool ok = true;
  if (o.voxel_size_check) {
    const auto start = Clock::now();
    const EsdfMap reference = computeEsdfReference(tsdf, config);
    const double reference_ms = msSince(start);
    const EsdfAgreement a = compareEsdfWithReference(host, reference);
    ok = a.ok();
    s << " Against the C++ reference (" << reference_ms
      << " ms): " << (a.compared > 0 ? 100.0 * a.over_voxel / a.compared : 0.0) << " % of "
      << a.compared
      << " voxels within the max distance differ by more than one voxel (limit "
      << 100.0 * kEsdfMaxShareOverVoxel << " %), mean " << a.mean_abs_voxels << " voxel (limit "
      << kEsdfMaxMeanErrorVoxels << "): " << (ok ? "ok" : "FAILED") << ".";
  }
  std::printf("%s\n", s.str().c_str());
  return ok ? 0 : 1;
}

}  // namespace

CLI::App* addEsdfCommand(CLI::App& app, EsdfOptions& o) {
  CLI::App* esdf = app.add_subcommand("esdf", "Compute a saved map's ESDF, write a slice picture");
  esdf->add_option("map", o.map_path, "Map file (.strata)")->required();
  esdf->add_option("--slice-z", o.slice_z_m, "Height of the slice, metres")
      ->check(finiteNumber())
      ->capture_default_str();
  esdf->add_option("--png", o.png_path, "Write the colour-mapped slice here (PNG)");
  esdf->add_option("--max-distance", o.max_distance_m,
                   "ESDF maximum distance (also caps the colour range), metres")
      ->check(finiteNumber())
      ->capture_default_str();
  esdf->add_flag("--voxel-size-check", o.voxel_size_check,
                 "Compare with the C++ reference: at most 0.2 % of voxels off by over one voxel");
  esdf->add_option("--device", o.device,
                   "Vulkan device index or name substring (env STRATA_DEVICE)");
  return esdf;
}

int runEsdf(const EsdfOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata esdf: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata esdf: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata esdf: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps

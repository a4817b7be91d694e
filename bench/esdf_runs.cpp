#include "esdf_runs.h"

#include <chrono>
#include <cstdio>

#include "strata/esdf/esdf_compare.h"
#include "esdf_queries.h"
#include "fuse_runs.h"  // kWarmupFrames
#include "strata/integrate/device_fusion.h"
#include "summary.h"
#include "bench_timing.h"

namespace strata::bench {
namespace {

constexpr std::size_t kProgressEvery = 25;  // frames between progress lines

std::size_t knownVoxels(const EsdfMap& map) {
  std::size_t known = 0;
  for (const auto& [b, block] : map.blocks) {
    for (const EsdfVoxel& v : block) known += esdfObserved(v) ? 1 : 0;
  }
  return known;
}

/// Fuses the frames, updating the ESDF incrementally from each frame's touched blocks.
void fuseWithEsdf(const Dataset& data, const EsdfBenchSettings& s, DeviceFusion& fusion,
                  DeviceEsdf& esdf, EsdfRun& run) {
  const std::size_t count = std::min(s.frames, data.size());
  for (std::size_t i = 0; i < count; ++i) {
    const FrameStats fs = fusion.integrate(data.load(i), data.intrinsics());
    run.fusion_device_ms.push_back(fs.normals_ms + fs.allocate_ms + fs.integrate_ms);
    esdf.markDirty(fusion.lastTouchedBlocks());
    run.incremental.push_back(esdf.updateIncremental());
    if ((i + 1) % kProgressEvery == 0 || i + 1 == count) {
      std::fprintf(stderr, "  %s: frame %zu/%zu, %u blocks, ESDF %.1f ms\n", run.input.c_str(),
                   i + 1, count, fusion.map().blockCount(), run.incremental.back().device_ms);
    }
  }
}

Json agreementJson(const EsdfAgreement& a) {
  return Json::object()
      .set("voxels_compared", a.compared)
      .set("share_over_one_voxel", a.compared > 0 ? double(a.over_voxel) / a.compared : 0.0)
      .set("mean_abs_error_voxels", a.mean_abs_voxels)
      .set("within_issue_tolerance", a.ok());
}

template <typename Field>
std::vector<double> values(const std::vector<EsdfUpdateStats>& stats, std::size_t first,
                           Field field) {
  std::vector<double> out;
  for (std::size_t i = first; i < stats.size(); ++i) out.push_back(field(stats[i]));
  return out;
}

/// sum(voxels recomputed) / sum(device seconds) over stats[first, end).
double voxelsPerSecond(const std::vector<EsdfUpdateStats>& stats, std::size_t first) {
  double voxels = 0.0, ms = 0.0;
  for (std::size_t i = first; i < stats.size(); ++i) {
    voxels += static_cast<double>(stats[i].voxels_updated);
    ms += stats[i].device_ms;
  }
  return ms > 0.0 ? voxels / (ms / 1000.0) : 0.0;
}

Json updateJson(const std::vector<EsdfUpdateStats>& stats, std::size_t first) {
  return Json::object()
      .set("runs_measured", stats.size() > first ? stats.size() - first : 0)
      .set("device_ms", meanMedian(values(stats, first, [](auto& s) { return s.device_ms; })))
      .set("wall_ms", meanMedian(values(stats, first, [](auto& s) { return s.wall_ms; })))
      .set("blocks_updated",
           meanMedian(values(stats, first, [](auto& s) { return double(s.blocks_updated); })))
      .set("voxels_updated",
           meanMedian(values(stats, first, [](auto& s) { return double(s.voxels_updated); })))
      .set("updated_voxels_per_s", voxelsPerSecond(stats, first));
}

}  // namespace

EsdfRun runEsdfBench(const std::string& input, const Dataset& data, const EsdfBenchSettings& s) {
  vk::ContextOptions options;
  options.device_selector = s.device;
  options.log_device = false;
  auto context = vk::Context::create(options);
  EsdfRun run;
  run.input = input;
  run.device_name = context->deviceName();
  DeviceFusion fusion(*context, s.map);
  fusion.setTrackTouchedBlocks(true);
  DeviceEsdf esdf(*context, fusion.map(), s.esdf);
  fuseWithEsdf(data, s, fusion, esdf, run);
  for (int i = 0; i < s.full_runs; ++i) run.full.push_back(esdf.updateAll());
  run.blocks = fusion.map().blockCount();

  std::fprintf(stderr, "  %s: C++ reference\n", input.c_str());
  TsdfMap tsdf(s.map);
  fusion.map().download(tsdf);
  const auto start = Clock::now();
  const EsdfMap reference = computeEsdfReference(tsdf, s.esdf);
  run.reference_ms = msSince(start);
  EsdfMap device_map;
  esdf.download(device_map);
  run.known_voxels = knownVoxels(device_map);
  const EsdfAgreement agreement = compareEsdfWithReference(device_map, reference);
  run.agreement = agreementJson(agreement);
  run.ok = run.blocks > 0 && agreement.compared > 0 && agreement.ok();

  std::fprintf(stderr, "  %s: queries and slice\n", input.c_str());
  run.queries = benchQueries(*context, esdf, device_map, s, run.ok);
  run.slice = benchSlice(device_map);
  return run;
}

Json esdfRunReport(const EsdfRun& run) {
  const double full_ms =
      run.full.empty() ? 0.0 : median(values(run.full, 0, [](auto& s) { return s.device_ms; }));
  return Json::object()
      .set("input", run.input)
      .set("frames", run.incremental.size())
      .set("blocks", run.blocks)
      .set("voxels", static_cast<std::uint64_t>(run.blocks) * kVoxelsPerBlock)
      .set("known_voxels", run.known_voxels)
      .set("fusion_device_ms_per_frame",
           meanMedian(std::vector<double>(
               run.fusion_device_ms.begin() +
                   std::min<std::ptrdiff_t>(kWarmupFrames, run.fusion_device_ms.size()),
               run.fusion_device_ms.end())))
      .set("incremental_per_frame", updateJson(run.incremental, kWarmupFrames))
      .set("full_recomputation", updateJson(run.full, 0))
      .set("cpu_reference_full_ms", run.reference_ms)
      .set("full_speedup_over_cpu_reference", full_ms > 0.0 ? run.reference_ms / full_ms : 0.0)
      .set("device_vs_reference", run.agreement)
      .set("queries", run.queries)
      .set("slice_picture", run.slice)
      .set("checks_passed", run.ok);
}

}  // namespace strata::bench

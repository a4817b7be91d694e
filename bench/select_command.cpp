#include "select_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "strata/core/clock.h"
#include "strata/core/error.h"
#include "strata/core/statistics.h"
#include "strata/integrate/device_fusion.h"
#include "json.h"
#include "machine_info.h"
#include "strata/select/keyframe_scorer.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata::bench {
namespace {

using Clock = std::chrono::steady_clock;

// Fixed scene so runs compare: the room's session 0 as the map, session 1's keyframes scored.
constexpr int kStrides[] = {10, 1};
constexpr int kSelfCheckKeyframes = 3;

struct SelectScene {
  std::unique_ptr<vk::Context> context;
  std::shared_ptr<sim::SimSessionDataset> map_session;
  std::shared_ptr<sim::SimSessionDataset> new_session;
  std::unique_ptr<DeviceFusion> fusion;
};

SelectScene makeScene(const SelectBenchOptions& o) {
  if (o.map_frames < 1 || o.keyframes < 1)
    throw InputError("--map-frames/--keyframes must be >= 1");
  SelectScene s;
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  s.context = vk::Context::create(context_options);
  const auto world = std::make_shared<const sim::World>(sim::World::load(sim::findWorld(o.world)));
  if (world->sessionCount() < 2) throw InputError("world '" + o.world + "' has one session");
  sim::SimSessionConfig config;
  config.max_frames = o.map_frames;
  s.map_session = std::make_shared<sim::SimSessionDataset>(world, 0, config);
  config.max_frames = o.keyframes;
  s.new_session = std::make_shared<sim::SimSessionDataset>(world, 1, config);
  MapConfig map;
  map.voxel_size_m = o.voxel_size_m;
  map.weight_mode = WeightMode::kConstant;
  map.allocate_free_space = true;
  map.validate();
  s.fusion = std::make_unique<DeviceFusion>(*s.context, map);
  std::fprintf(stderr, "select: fusing %zu keyframes of %s\n", s.map_session->size(),
               s.map_session->name().c_str());
  for (std::size_t i = 0; i < s.map_session->size(); ++i) {
    s.fusion->integrate(s.map_session->load(i), s.map_session->intrinsics());
  }
  return s;
}

Json runStride(SelectScene& s, const std::vector<RgbdFrame>& frames, int stride, bool* ok) {
  selection::ScorerConfig config;
  config.sample_stride_px = stride;
  selection::KeyframeScorer scorer(*s.context, config);
  std::vector<double> device_ms, wall_ms;
  double coverage = 0.0;
  int samples = 0;
  std::size_t checked = 0, mismatches = 0;
  TsdfMap host(s.fusion->config());
  if (stride == kStrides[0]) s.fusion->map().download(host);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    double ms = 0.0;
    SampleRaycast device;
    const auto start = Clock::now();
    const auto score =
        scorer.score(s.fusion->map(), frames[i], s.new_session->intrinsics(), &ms, &device);
    wall_ms.push_back(msSince(start));
    device_ms.push_back(ms);
    coverage += score.coverage;
    samples = score.samples;
    if (stride != kStrides[0] || i >= kSelfCheckKeyframes) continue;
    SampleRaycast reference;
    selection::scoreKeyframeReference(host, frames[i], s.new_session->intrinsics(), config,
                                      &reference);
    for (std::size_t k = 0; k < device.hit.size(); ++k)
      mismatches += device.hit[k] != reference.hit[k];
    checked += device.hit.size();
  }
  Json out = Json::object()
                 .set("stride_px", stride)
                 .set("samples_per_keyframe", samples)
                 .set("keyframes", static_cast<int>(frames.size()))
                 .set("keyframes_per_s_device", 1000.0 / mean(device_ms))
                 .set("device_ms_mean", mean(device_ms))
                 .set("device_ms_median", median(device_ms))
                 .set("wall_ms_mean", mean(wall_ms))
                 .set("mean_coverage", coverage / frames.size());
  if (checked > 0) {
    const double agreement = 1.0 - static_cast<double>(mismatches) / checked;
    *ok = *ok && agreement >= 0.999;
    out.set("self_check_hit_agreement", agreement);
  }
  return out;
}

int runChecked(const SelectBenchOptions& o) {
  const std::string load_at_start = loadAverage();
  SelectScene scene = makeScene(o);
  std::vector<RgbdFrame> frames;
  for (std::size_t i = 0; i < scene.new_session->size(); ++i) {
    frames.push_back(scene.new_session->load(i));
  }
  bool ok = true;
  Json runs = Json::array();
  for (int stride : kStrides) {
    std::fprintf(stderr, "select: scoring %zu keyframes every %d px\n", frames.size(), stride);
    runs.push(runStride(scene, frames, stride, &ok));
  }
  const Json settings =
      Json::object()
          .set("world", o.world)
          .set("map", "session 0, " + std::to_string(scene.map_session->size()) + " keyframes, " +
                          scene.fusion->config().describe())
          .set("scored", "session 1, " + std::to_string(frames.size()) + " keyframes at 640x480")
          .set("notes",
               Json::array()
                   .push("device time: timestamp queries around raycast_samples.comp and "
                         "sample_differences.comp (one dispatch each per keyframe); wall time "
                         "adds uploads, readbacks and the host's upper-half means and baselines")
                   .push("on lavapipe the device is this CPU (LP_NUM_THREADS threads); "
                         "timings are noisy when other work shares the cores"));
  Json report = Json::object()
                    .set("benchmark", "select")
                    .set("machine", machineInfo(scene.context->deviceName(), load_at_start))
                    .set("settings", settings)
                    .set("runs", runs)
                    .set("checks_passed", ok);
  emitReport(report, o.out_path);
  if (!ok) std::fprintf(stderr, "strata-bench select: device and reference hit masks differ\n");
  return ok ? 0 : 1;
}

}  // namespace

CLI::App* addSelectCommand(CLI::App& app, SelectBenchOptions& o) {
  CLI::App* c = app.add_subcommand("select", "Keyframe selection: keyframes scored per second");
  c->add_option("--world", o.world, "World name or YAML path")->capture_default_str();
  c->add_option("--voxel-size", o.voxel_size_m, "Voxel edge, metres")->capture_default_str();
  c->add_option("--map-frames", o.map_frames, "Session-0 keyframes fused into the map")
      ->capture_default_str();
  c->add_option("--keyframes", o.keyframes, "Session-1 keyframes scored")->capture_default_str();
  c->add_option("--out", o.out_path, "Also write the JSON report here (atomically)");
  c->add_option("--device", o.device, "Vulkan device index or name substring");
  return c;
}

int runSelectBench(const SelectBenchOptions& o) {
  try {
    return runChecked(o);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench select: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata-bench select: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench select: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

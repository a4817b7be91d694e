#include "explore_gain_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include "strata/core/clock.h"
#include "strata/core/error.h"
#include "strata/core/statistics.h"
#include "strata/explore/view_gain.h"
#include "strata/integrate/device_fusion.h"
#include "json.h"
#include "machine_info.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata::bench {
namespace {

using Clock = std::chrono::steady_clock;

// Fixed scene so runs compare: session 0 of the world fused as the map; candidate positions drawn
// with this seed in the world's bounds at flying heights, kept where the truth is free by at
// least kClearance_m.
constexpr std::uint32_t kPositionSeed = 17;
constexpr float kMinHeight_m = 0.8f, kMaxHeight_m = 1.8f;
constexpr float kClearance_m = 0.3f;

struct GainScene {
  std::unique_ptr<vk::Context> context;
  std::shared_ptr<const sim::World> world;
  std::unique_ptr<DeviceFusion> fusion;
  std::size_t frames = 0;
};

GainScene makeScene(const ExploreGainBenchOptions& o) {
  if (o.map_frames < 1 || o.repeats < 1 || o.reference_positions < 1 || o.batches.empty() ||
      *std::min_element(o.batches.begin(), o.batches.end()) < 1) {
    throw InputError("--map-frames, --repeats, --reference-positions and --batches must be >= 1");
  }
  GainScene s;
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  s.context = vk::Context::create(context_options);
  s.world = std::make_shared<const sim::World>(sim::World::load(sim::findWorld(o.world)));
  sim::SimSessionConfig config;
  config.max_frames = o.map_frames;
  const sim::SimSessionDataset session(s.world, 0, config);
  MapConfig map;
  map.voxel_size_m = o.voxel_size_m;
  map.allocate_free_space = true;  // free space observed, as exploration needs
  map.validate();
  s.fusion = std::make_unique<DeviceFusion>(*s.context, map);
  std::fprintf(stderr, "explore-gain: fusing %zu keyframes of %s\n", session.size(),
               session.name().c_str());
  for (std::size_t i = 0; i < session.size(); ++i) {
    s.fusion->integrate(session.load(i), session.intrinsics());
  }
  s.frames = session.size();
  return s;
}

std::vector<Eigen::Vector3f> freePositions(const sim::World& world, std::size_t count) {
  const auto scene = world.buildScene(0);
  const Eigen::AlignedBox3d bounds = world.bounds();
  std::mt19937 rng(kPositionSeed);
  std::uniform_real_distribution<float> x(bounds.min().x(), bounds.max().x());
  std::uniform_real_distribution<float> y(bounds.min().y(), bounds.max().y());
  std::uniform_real_distribution<float> z(kMinHeight_m, kMaxHeight_m);
  std::vector<Eigen::Vector3f> positions;
  for (std::size_t tries = 0; positions.size() < count && tries < 1000 * count; ++tries) {
    const Eigen::Vector3f p(x(rng), y(rng), z(rng));
    if (scene->signedDistance(p) > kClearance_m) positions.push_back(p);
  }
  if (positions.size() < count) throw InputError("too few free positions in the world");
  return positions;
}

bool sameGains(const std::vector<explore::ViewGain>& a, const std::vector<explore::ViewGain>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a[i].bin_gain_m3 != b[i].bin_gain_m3 || a[i].best_yaw_rad != b[i].best_yaw_rad) {
      return false;
    }
  }
  return true;
}

Json runBatch(GainScene& s, explore::ViewGainKernel& kernel, const std::vector<Eigen::Vector3f>& all,
              int batch, int repeats) {
  const std::vector<Eigen::Vector3f> positions(all.begin(), all.begin() + batch);
  std::vector<double> device_ms, wall_ms;
  double mean_best_m3 = 0.0;
  for (int r = 0; r < repeats; ++r) {
    double ms = 0.0;
    const auto start = Clock::now();
    const std::vector<explore::ViewGain> gains = kernel.run(s.fusion->map(), positions, &ms);
    wall_ms.push_back(msSince(start));
    device_ms.push_back(ms);
    mean_best_m3 = 0.0;
    for (const explore::ViewGain& g : gains) mean_best_m3 += g.best_gain_m3 / gains.size();
  }
  const double ms = median(device_ms);
  return Json::object()
      .set("positions", batch)
      .set("device_ms_median", ms)
      .set("device_ms_per_100_positions", ms * 100.0 / batch)
      .set("positions_per_s_device", batch * 1000.0 / ms)
      .set("wall_ms_median", median(wall_ms))
      .set("mean_best_gain_m3", mean_best_m3);
}

int runChecked(const ExploreGainBenchOptions& o) {
  const std::string load_at_start = loadAverage();
  GainScene scene = makeScene(o);
  const int most =
      std::max(*std::max_element(o.batches.begin(), o.batches.end()), o.reference_positions);
  const std::vector<Eigen::Vector3f> positions = freePositions(*scene.world, most);
  const explore::ViewGainConfig config;
  explore::ViewGainKernel kernel(*scene.context, config);
  Json runs = Json::array();
  for (int batch : o.batches) {
    std::fprintf(stderr, "explore-gain: %d positions x %d\n", batch, o.repeats);
    runs.push(runBatch(scene, kernel, positions, batch, o.repeats));
  }

  const std::vector<Eigen::Vector3f> checked(positions.begin(),
                                             positions.begin() + o.reference_positions);
  TsdfMap host(scene.fusion->config());
  scene.fusion->map().download(host);
  const auto start = Clock::now();
  const std::vector<explore::ViewGain> reference =
      explore::viewGainReference(host, config, checked);
  const double reference_ms =
      msSince(start);
  const bool ok = sameGains(kernel.run(scene.fusion->map(), checked), reference);

  const Json settings =
      Json::object()
          .set("world", o.world)
          .set("map", "session 0, " + std::to_string(scene.frames) + " keyframes, " +
                          scene.fusion->config().describe() + ", " +
                          std::to_string(scene.fusion->map().blockCount()) + " blocks")
          .set("fan", std::to_string(config.yaw_bins) + " yaw bins x " +
                          std::to_string(config.rays_per_bin) + " rays x " +
                          std::to_string(config.elevation_rays) + " rows, " +
                          std::to_string(config.min_range_m) + "-" +
                          std::to_string(config.max_range_m) + " m, step " +
                          std::to_string(config.step_voxels) + " voxel")
          .set("notes",
               Json::array()
                   .push("device time: timestamp queries around view_gain.comp (one dispatch per "
                         "batch); wall time adds the uploads, the readback and the host's windows")
                   .push("on lavapipe the device is this CPU (LP_NUM_THREADS threads); "
                         "timings are noisy when other work shares the cores"));
  Json report = Json::object()
                    .set("benchmark", "explore-gain")
                    .set("machine", machineInfo(scene.context->deviceName(), load_at_start))
                    .set("settings", settings)
                    .set("runs", runs)
                    .set("reference",
                         Json::object()
                             .set("positions", o.reference_positions)
                             .set("host_ms", reference_ms)
                             .set("positions_per_s", o.reference_positions * 1000.0 / reference_ms))
                    .set("checks_passed", ok);
  emitReport(report, o.out_path);
  if (!ok) std::fprintf(stderr, "strata-bench explore-gain: device and reference differ\n");
  return ok ? 0 : 1;
}

}  // namespace

CLI::App* addExploreGainCommand(CLI::App& app, ExploreGainBenchOptions& o) {
  CLI::App* c = app.add_subcommand("explore-gain", "View gain: positions scored per second");
  c->add_option("--world", o.world, "World name or YAML path")->capture_default_str();
  c->add_option("--voxel-size", o.voxel_size_m, "Voxel edge, metres")->capture_default_str();
  c->add_option("--map-frames", o.map_frames, "Session-0 keyframes fused into the map")
      ->capture_default_str();
  c->add_option("--batches", o.batches, "Positions per dispatch")->capture_default_str();
  c->add_option("--repeats", o.repeats, "Dispatches per batch size")->capture_default_str();
  c->add_option("--reference-positions", o.reference_positions,
                "Positions timed on the host and compared")
      ->capture_default_str();
  c->add_option("--out", o.out_path, "Also write the JSON report here (atomically)");
  c->add_option("--device", o.device, "Vulkan device index or name substring");
  return c;
}

int runExploreGainBench(const ExploreGainBenchOptions& o) {
  try {
    return runChecked(o);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench explore-gain: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata-bench explore-gain: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench explore-gain: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

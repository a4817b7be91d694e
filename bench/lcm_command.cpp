#include "lcm_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>

#include "strata/core/error.h"
#include "lcm_runs.h"
#include "machine_info.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world.h"
#include "strata/sim/world/world_paths.h"

namespace strata::bench {
namespace {

// Windows measured: 1 = latency with nothing queued; 3 = receive/decode overlapping fusion.
constexpr int kWindows[] = {1, 3};

apps::MapperOptions mapperOptions(const LcmBenchOptions& o) {
  apps::MapperOptions m;
  m.url = o.url;
  m.map.voxel_size_m = o.voxel_size_m;
  m.map_path.clear();
  m.mesh_rate_hz = 0.0;  // a mesh update after every frame: what the latency measures
  m.esdf_rate_hz = 0.0;
  m.change_detection = o.change_detection;
  m.quiet = true;
  m.validate();
  return m;
}

std::vector<RgbdFrame> renderFrames(int count, CameraIntrinsics* intrinsics) {
  const auto world = std::make_shared<const sim::World>(sim::World::load(sim::findWorld("room")));
  sim::SimSessionConfig config;
  config.max_frames = count;
  const sim::SimSessionDataset session(world, 0, config);
  *intrinsics = session.intrinsics();
  std::vector<RgbdFrame> frames;
  for (std::size_t i = 0; i < session.size(); ++i) frames.push_back(session.load(i));
  return frames;
}

Json report(const LcmBenchOptions& o, const CameraIntrinsics& k, const std::string& device,
            const std::string& load, const Json& runs) {
  return Json::object()
      .set("benchmark", "lcm")
      .set("transport", o.url)
      .set("resolution", std::to_string(k.width_px) + "x" + std::to_string(k.height_px))
      .set("depth_encoding", o.depth_encoding)
      .set("colour", "rgb8")
      .set("frames", o.frames)
      .set("scene", "room world, session 0 (synthetic, noise on)")
      .set("voxel_size_m", static_cast<double>(o.voxel_size_m))
      .set("free_space_allocated", true)
      .set("change_detection", o.change_detection)
      .set("mesh_updates", "after every fused frame, changed blocks and their neighbours")
      .set("runs", runs)
      .set("machine", machineInfo(device, load));
}

}  // namespace

CLI::App* addLcmCommand(CLI::App& app, LcmBenchOptions& o) {
  CLI::App* lcm = app.add_subcommand(
      "lcm", "End to end over LCM: frames per second and publish -> mesh update latency");
  lcm->add_option("--url", o.url, "LCM URL (memq:// in-process; udpm://...?ttl=0 via loopback)")
      ->capture_default_str();
  lcm->add_option("--frames", o.frames, "Frames (640x480 RGB-D, rendered before timing)")
      ->capture_default_str();
  lcm->add_option("--voxel-size", o.voxel_size_m, "Voxel edge, metres")->capture_default_str();
  lcm->add_option("--depth-encoding", o.depth_encoding, "depth16 or depth32f")
      ->capture_default_str();
  lcm->add_flag("--change", o.change_detection,
                "Include change detection (strata-mapper's default)");
  lcm->add_option("--out", o.out_path, "Also write the JSON here");
  lcm->add_option("--device", o.device, "Vulkan device index or name substring");
  return lcm;
}

int runLcmBench(const LcmBenchOptions& o) {
  try {
    if (o.frames < 2) throw InputError("--frames must be at least 2");
    const std::string load = loadAverage();
    CameraIntrinsics intrinsics;
    std::fprintf(stderr, "strata-bench lcm: rendering %d frames\n", o.frames);
    const std::vector<RgbdFrame> frames = renderFrames(o.frames, &intrinsics);
    vk::ContextOptions context_options;
    context_options.device_selector = o.device;
    context_options.log_device = false;
    auto context = vk::Context::create(context_options);
    LcmRunSettings settings{o.url, mapperOptions(o), o.depth_encoding, 1};
    Json runs = Json::array();
    bool complete = true;
    for (int window : kWindows) {
      settings.window = window;
      std::fprintf(stderr, "strata-bench lcm: window %d\n", window);
      const LcmRun run = runLcm(*context, frames, intrinsics, settings);
      complete = complete && run.frames_fused + run.frames_dropped ==
                                 static_cast<std::int64_t>(run.frames_sent);
      runs.push(lcmRunJson(run));
    }
    emitReport(report(o, intrinsics, context->deviceName(), load, runs), o.out_path);
    if (!complete) std::fprintf(stderr, "strata-bench lcm: frames went missing (self-check)\n");
    return complete ? 0 : 1;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench lcm: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata-bench lcm: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench lcm: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

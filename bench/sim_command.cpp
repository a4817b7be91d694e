#include "sim_command.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>

#include "strata/core/error.h"
#include "json.h"
#include "machine_info.h"
#include "strata/sim/sensors/grey_camera.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/session/stereo_recording.h"
#include "strata/sim/world/world_paths.h"

namespace strata::bench {
namespace {

using Clock = std::chrono::steady_clock;
// Frames rendered before timing: the first frame builds the shared Embree scenes.
constexpr int kSimWarmupFrames = 2;

Json benchWorld(const std::string& name, const SimBenchOptions& o) {
  const auto world = std::make_shared<const sim::World>(sim::World::load(sim::findWorld(name)));
  sim::SimSessionConfig config;
  config.max_frames = o.frames + kSimWarmupFrames;
  config.camera.noise.enabled = o.noise;
  const auto build_start = Clock::now();
  const sim::SimSessionDataset session(world, 0, config);
  const double setup_s = std::chrono::duration<double>(Clock::now() - build_start).count();
  for (int i = 0; i < kSimWarmupFrames; ++i) session.render(static_cast<std::size_t>(i));
  std::size_t valid_pixels = 0;
  const auto start = Clock::now();
  for (std::size_t i = kSimWarmupFrames; i < session.size(); ++i) {
    const sim::SimulatedFrame frame = session.render(i);
    for (float d : frame.depth.depth_m) valid_pixels += d > 0.0f ? 1 : 0;
  }
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  const double frames = static_cast<double>(session.size() - kSimWarmupFrames);
  // The grey stereo pair of `strata sim --stereo` (752x480, exposure and pixel noise), at the
  // same poses; rendering only (the PNG files are not written).
  const sim::StereoRecordingConfig stereo;
  sim::GreyCameraConfig grey;
  grey.intrinsics.width_px = stereo.width_px;
  grey.intrinsics.height_px = stereo.height_px;
  grey.intrinsics.fx_px = grey.intrinsics.fy_px = static_cast<float>(0.61 * stereo.width_px);
  grey.intrinsics.cx_px = 0.5f * static_cast<float>(stereo.width_px - 1);
  grey.intrinsics.cy_px = 0.5f * static_cast<float>(stereo.height_px - 1);
  grey.baseline_m = stereo.baseline_m;
  grey.exposure_gain_sigma = stereo.exposure_gain_sigma;
  grey.exposure_offset_sigma = stereo.exposure_offset_sigma;
  const sim::GreyCamera grey_camera(grey);
  const auto grey_start = Clock::now();
  for (std::size_t i = kSimWarmupFrames; i < session.size(); ++i) {
    grey_camera.render(session.scene(), session.truePoses()[i], session.lighting(), i);
  }
  const double grey_s = std::chrono::duration<double>(Clock::now() - grey_start).count();
  std::fprintf(stderr, "strata-bench sim: %s %.1f grey stereo pairs/s\n", name.c_str(),
               frames / grey_s);
  std::fprintf(stderr, "strata-bench sim: %s %.1f frames/s\n", name.c_str(), frames / seconds);
  if (valid_pixels == 0) throw Error("world '" + name + "' rendered no valid depth at all");
  return Json::object()
      .set("world", name)
      .set("objects", world->objectCount())
      .set("frames", static_cast<int>(frames))
      .set("resolution", std::to_string(config.camera.intrinsics.width_px) + "x" +
                             std::to_string(config.camera.intrinsics.height_px))
      .set("noise", o.noise)
      .set("session_setup_s", setup_s)
      .set("frames_per_s", frames / seconds)
      .set("ms_per_frame", 1000.0 * seconds / frames)
      .set("grey_stereo_resolution", std::to_string(grey.intrinsics.width_px) + "x" +
                                         std::to_string(grey.intrinsics.height_px))
      .set("grey_stereo_pairs_per_s", frames / grey_s)
      .set("valid_depth_share", static_cast<double>(valid_pixels) /
                                    (frames * config.camera.intrinsics.width_px *
                                     config.camera.intrinsics.height_px));
}

}  // namespace

CLI::App* addSimCommand(CLI::App& app, SimBenchOptions& o) {
  CLI::App* sim = app.add_subcommand("sim", "Simulated RGB-D and grey stereo rendering speed per shipped world");
  sim->add_option("--worlds", o.worlds, "World names or files")->delimiter(',');
  sim->add_option("--frames", o.frames, "Frames timed per world")->capture_default_str();
  sim->add_flag("!--no-noise", o.noise, "Render exact depth");
  sim->add_option("--out", o.out_path, "Also write the JSON here");
  return sim;
}

int runSimBench(const SimBenchOptions& o) {
  try {
    const std::string load_at_start = loadAverage();
    Json results = Json::array();
    for (const std::string& name : o.worlds) results.push(benchWorld(name, o));
    Json report = Json::object()
                      .set("benchmark", "sim")
                      .set("machine", machineInfo("host CPU (Embree ray casting)", load_at_start))
                      .set("warmup_frames_excluded", kSimWarmupFrames)
                      .set("results", results);
    emitReport(report, o.out_path);
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench sim: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench sim: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

#include "apps/demo_command.h"

#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "apps/demo_report.h"
#include "apps/progress.h"
#include "apps/sim_setup.h"
#include "apps/views.h"
#include "core/error.h"
#include "eval/accuracy.h"
#include "io/image_io.h"
#include "kernels/raycast.h"
#include "kernels/device_fusion.h"
#include "mesh/extract_mesh.h"
#include "mesh/ply.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

SessionResult runSession(vk::Context& context, const sim::SimSessionDataset& session,
                         const MapConfig& map_config, const fs::path& out, ProgressBar& progress,
                         std::size_t& done) {
  SessionResult result;
  result.session = session.session();
  result.frames = session.size();
  DeviceFusion fusion(context, map_config);
  for (std::size_t i = 0; i < session.size(); ++i) {
    const auto render_start = Clock::now();
    const RgbdFrame frame = session.load(i);
    result.render_s += secondsSince(render_start);
    const FrameStats stats = fusion.integrate(frame, session.intrinsics());
    result.fuse_wall_ms += stats.wall_ms;
    result.fuse_device_ms += stats.normals_ms + stats.allocate_ms + stats.integrate_ms;
    progress.update(++done);
  }
  TsdfMap map(map_config);
  fusion.map().download(map);
  result.blocks = map.blockCount();
  const Mesh mesh = extractMesh(map);
  result.mesh_vertices = mesh.vertices.size();
  const auto truth = [&](const Eigen::Vector3d& p) {
    return static_cast<double>(session.scene().signedDistance(p.cast<float>()));
  };
  result.tsdf = eval::evaluateTsdf(map, truth, 0.5f * map_config.truncationDistance());
  result.mesh = eval::evaluateMesh(mesh, truth, map_config.voxel_size_m);
  const std::string stem = "session_" + std::to_string(session.session());
  writePly((out / (stem + "_mesh.ply")).string(), mesh);
  // A picture of the fused map from the session's first pose.
  RaycastKernel raycast(context);
  const Eigen::Isometry3d& T_W_C = session.givenPoses().front();
  writeColorPng((out / (stem + "_view.png")).string(),
                shadedView(raycast.run(fusion.map(), session.intrinsics(), T_W_C), T_W_C));
  writePly((out / (stem + "_truth.ply")).string(), session.world().sessionMesh(session.session()));
  result.changed_ids = session.world().session(session.session()).changedIds();
  return result;
}

}  // namespace

CLI::App* addDemoCommand(CLI::App& app, DemoOptions& o) {
  CLI::App* demo = app.add_subcommand("demo", "Multi-session demo on a synthetic world");
  demo->add_option("world", o.world, "World file (YAML); default: the shipped single room");
  demo->add_option("--sessions", o.sessions, "Sessions (default: the world's)");
  demo->add_option("--out", o.out_dir, "Output folder")->capture_default_str();
  demo->add_option("--seed", o.seed, "Override the world's seed");
  demo->add_option("--frames", o.frames, "Frames per session")->capture_default_str();
  demo->add_option("--voxel-size", o.voxel_size_m, "Voxel edge, metres")->capture_default_str();
  demo->add_flag("--no-noise", o.no_noise, "Exact depth");
  demo->add_option("--device", o.device, "Vulkan device index or name substring");
  demo->add_flag("--quiet", o.quiet, "No progress bar");
  return demo;
}

int runDemo(const DemoOptions& o) {
  try {
    const auto start = Clock::now();
    const auto world = loadWorld(o.world, o.seed, o.sessions);
    const sim::SimSessionConfig config = sessionConfig(30.0, o.frames, !o.no_noise, false);
    MapConfig map_config;
    map_config.voxel_size_m = o.voxel_size_m;
    map_config.validate();
    vk::ContextOptions context_options;
    context_options.device_selector = o.device;
    const auto context = vk::Context::create(context_options);
    const fs::path out(o.out_dir);
    fs::create_directories(out);
    DemoReport report{world->name(), world->seed(), map_config.describe(), context->deviceName()};
    std::vector<std::unique_ptr<sim::SimSessionDataset>> sessions;
    std::size_t total = 0;
    for (int s = 0; s < world->sessionCount(); ++s) {
      sessions.push_back(std::make_unique<sim::SimSessionDataset>(world, s, config));
      total += sessions.back()->size();
    }
    ProgressBar progress("simulate + fuse", total, !o.quiet);
    std::size_t done = 0;
    for (const auto& session : sessions) {
      report.sessions.push_back(runSession(*context, *session, map_config, out, progress, done));
    }
    progress.finish();
    report.total_s = secondsSince(start);
    writeDemoReport(report, (out / "report.json").string());
    std::printf("%s\n", summarizeDemo(report, o.out_dir).c_str());
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata demo: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata demo: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata demo: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps

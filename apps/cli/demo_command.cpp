#include "cli/demo_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <future>

#include "cli/demo_objects.h"
#include "cli/demo_report.h"
#include "cli/diff_outputs.h"
#include "strata/core/clock.h"
#include "strata/mapper/session_diff.h"
#include "strata/core/progress.h"
#include "cli/select_incremental.h"
#include "strata/sim/sim_setup.h"
#include "cli/shaded_view.h"
#include "strata/change/eval/evaluation_session.h"
#include "strata/change/eval/evaluation_world.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/mapper/eval/accuracy.h"
#include "strata/io/image_io.h"
#include "strata/raycast/raycast.h"
#include "strata/mesh/ply.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;
using Sessions = std::vector<std::unique_ptr<change::RecordingSession>>;

/// A half-resolution view of a session's own map from its first pose (host raycast: the device
/// map's layer 0 is the static map).
ColorImage sessionView(const TsdfMap& map, const sim::SimSessionDataset& session) {
  CameraIntrinsics k = session.intrinsics();
  k.width_px /= 2;
  k.height_px /= 2;
  k.fx_px /= 2;
  k.fy_px /= 2;
  k.cx_px = (k.cx_px + 0.5f) / 2 - 0.5f;
  k.cy_px = (k.cy_px + 0.5f) / 2 - 0.5f;
  const Eigen::Isometry3d& T_W_C = session.givenPoses().front();
  return shadedView(raycastReference(map, k, T_W_C), T_W_C);
}

/// Accuracy against the session's true geometry, and the per-session files.
SessionResult sessionResult(const DiffSession& fused, const TsdfMap& map,
                            const sim::SimSessionDataset& session, const fs::path& out) {
  SessionResult r;
  r.session = session.session();
  r.frames = fused.frames;
  r.recorded_frames = session.recordedFrames();
  r.render_s = fused.load_s;
  r.fuse_wall_ms = fused.fuse_wall_ms;
  r.fuse_device_ms = fused.fuse_device_ms;
  r.blocks = map.blockCount();
  r.mesh_vertices = fused.surface.mesh.vertices.size();
  const auto truth = [&](const Eigen::Vector3d& p) {
    return static_cast<double>(session.scene().signedDistance(p.cast<float>()));
  };
  r.tsdf = eval::evaluateTsdf(map, truth, 0.5f * map.config().truncationDistance());
  r.mesh = eval::evaluateMesh(fused.surface.mesh, truth, map.config().voxel_size_m);
  r.changed_ids = session.world().session(session.session()).changedIds();
  r.objects = fused.objects.size();
  const std::string stem = "session_" + std::to_string(session.session());
  writePly((out / (stem + "_mesh.ply")).string(), fused.surface.mesh);
  writePly((out / (stem + "_truth.ply")).string(), session.world().sessionMesh(session.session()));
  writeColorPng((out / (stem + "_view.png")).string(), sessionView(map, session));
  return r;
}

change::WorldEvaluation evaluate(const sim::World& world, const DiffResult& result,
                                 const Sessions& sessions, const change::ChangeConfig& config) {
  std::vector<std::vector<change::DiscoveredObject>> objects;
  std::vector<const change::VisibleSurface*> seen;
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    objects.push_back(result.sessions[s].objects);
    seen.push_back(&sessions[s]->seen());
  }
  change::EvaluationConfig eval_config;
  // Constant weights: a voxel is observed from min_weight frames on; judge the truth alike.
  eval_config.min_views = config.minFrames();
  return change::evaluateWorld(world, objects, result.static_mesh, seen, eval_config);
}

/// The world's sessions; with --vio on poses from the VIO (`vio` receives what each run measured).
Sessions makeSessions(const std::shared_ptr<const sim::World>& world,
                      const sim::SimSessionConfig& config, const DemoOptions& o,
                      std::vector<VioSessionResult>& vio,
                      std::optional<DemoAlignResult>& alignment,
                      std::optional<DemoLocalizeResult>& localization) {
  std::vector<std::shared_ptr<sim::SimSessionDataset>> simulated;
  std::size_t stereo_frames = 0;
  for (int s = 0; s < world->sessionCount(); ++s) {
    simulated.push_back(std::make_shared<sim::SimSessionDataset>(world, s, config));
    if (o.vio.enabled) stereo_frames += vioFrameCount(*simulated.back(), o.vio);
  }
  if (o.vio.enabled) {
    ProgressBar progress("render grey stereo + VIO", stereo_frames, !o.quiet);
    std::size_t done = 0;
    for (const auto& session : simulated)
      vio.push_back(useVioPoses(*session, o.vio, !o.no_noise, progress, done));
    progress.finish();
  }
  if (o.align) alignment = useAlignedPoses(simulated, o.quiet);
  if (o.localize) localization = useLocalizedPoses(simulated, o.quiet);
  Sessions sessions;
  for (auto& session : simulated)
    sessions.push_back(std::make_unique<change::RecordingSession>(std::move(session)));
  return sessions;
}

/// Fuses every session (recording what it saw) and runs change detection.
DiffResult detectChanges(vk::Context& context, const MapConfig& map_config, const DiffRunInfo& info,
                         const Sessions& sessions, bool quiet, std::vector<TsdfMap>& maps) {
  std::size_t total = 0, done = 0;
  for (const auto& session : sessions) total += session->size();
  DiffPipeline pipeline(context, map_config, info.change, info.objects);
  ProgressBar progress("simulate + fuse + detect changes", total, !quiet);
  for (const auto& session : sessions)
    pipeline.addSession(*session, session->name(), progress, done);
  progress.finish();
  return pipeline.finish(&maps);
}

}  // namespace

DemoReport runDemoPipeline(const DemoOptions& o) {
  const auto start = Clock::now();
  if (o.incremental) {  // before minutes of fusion, not after
    selection::SelectionConfig check;
    check.smoothing_window = o.select.smoothing_window;
    check.dilation = o.select.dilation;
    check.validate();
  }
  if (o.vio.enabled) o.vio.validate();
  if (o.vio.enabled && o.align) throw InputError("--align and --vio cannot be combined (yet)");
  if (o.localize && (o.align || o.vio.enabled))
    throw InputError("--localize cannot be combined with --align or --vio (yet)");
  if (o.out_dir.empty()) throw InputError("--out DIR must not be empty");
  {  // The output folder before minutes of work: writable, not a file, not the world file.
    OutputPaths paths;
    if (!o.world.empty() && fs::is_regular_file(o.world)) {
      paths.inputFile(o.world, "the world file");
    }
    paths.outputFolder(o.out_dir, "--out");
    paths.check();
  }
  const auto world = sim::loadWorld(o.world, o.seed, o.sessions);
  sim::SimSessionConfig config =
      sim::sessionConfig(30.0, o.frames, !o.no_noise, o.align || o.localize);
  // Alignment finds places by ORB corners in the colour images: --align renders them with the
  // world-anchored texture real surfaces would have (flat shading leaves corners on edges only).
  if (o.align || o.localize) config.camera.color_texture = sim::WorldTextureConfig{};
  config.trajectory.rest_at_start_s = o.restSeconds();
  const MapConfig map_config = change::changeMapConfig(o.voxel_size_m);  // min_weight counts frames
  DiffRunInfo info;
  info.change.min_weight = o.min_weight;
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  const auto context = vk::Context::create(context_options);
  info.device = context->deviceName();
  info.map_config = map_config.describe();
  const fs::path out(o.out_dir);
  fs::create_directories(out);
  std::vector<VioSessionResult> vio;
  std::optional<DemoAlignResult> alignment;
  std::optional<DemoLocalizeResult> localization;
  const Sessions sessions = makeSessions(world, config, o, vio, alignment, localization);
  std::vector<TsdfMap> maps;
  const DiffResult result = detectChanges(*context, map_config, info, sessions, o.quiet, maps);
  const DiffFiles files = writeDiffFiles(result, o.out_dir);
  DemoReport report{world->name(), world->seed(), info.map_config, info.device};
  // Sessions in parallel: the ground-truth distance queries of the accuracy dominate, and the
  // scenes answer them from any thread.
  std::vector<std::future<SessionResult>> results;
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    results.push_back(std::async(std::launch::async, [&, s] {
      return sessionResult(result.sessions[s], maps[s], sessions[s]->session(), out);
    }));
  }
  for (std::size_t s = 0; s < results.size(); ++s) {
    report.sessions.push_back(results[s].get());
    if (s < vio.size()) report.sessions.back().vio = vio[s];
  }
  report.evaluation = evaluate(*world, result, sessions, info.change);
  report.alignment = alignment;
  report.localization = localization;
  if (o.incremental) {
    const IncrementalResult incremental =
        runIncremental(*context, *world, sessions, map_config, info, report.evaluation, o.out_dir,
                       o.quiet, o.select);
    report.incremental_summary = summarizeIncremental(incremental);
    report.incremental_json = incrementalJson(incremental);
    report.incremental = incremental;
  }
  if (o.objects) addDemoObjects(result, maps, world, o.out_dir, report);  // moved objects as models
  report.total_s = info.total_s = secondsSince(start);
  writeDemoReport(report, result, files, info, (out / "report.json").string());
  return report;
}

CLI::App* addDemoCommand(CLI::App& app, DemoOptions& o) {
  CLI::App* demo = app.add_subcommand("demo", "Multi-session demo on a synthetic world");
  demo->add_option("world", o.world, "World file (YAML); default: the shipped single room");
  demo->add_option("--sessions", o.sessions, "Sessions (default: the world's)");
  demo->add_option("--out", o.out_dir, "Output folder")->capture_default_str();
  demo->add_option("--seed", o.seed, "Override the world's seed");
  demo->add_option("--frames", o.frames, "Frames per session")->capture_default_str();
  demo->add_option("--voxel-size", o.voxel_size_m, "Voxel edge, metres")->capture_default_str();
  demo->add_option("--min-weight", o.min_weight,
                   "Frames a voxel must be seen in to count as observed")
      ->capture_default_str();
  demo->add_flag("--no-noise", o.no_noise, "Exact depth (and with --vio exact images and IMU)");
  demo->add_flag("--vio", o.vio.enabled,
                 "Fuse on poses from stereo visual-inertial odometry over each session's "
                 "simulated grey stereo + IMU (anchored at the true pose where tracking starts)");
  demo->add_flag("--align", o.align,
                 "Sessions drift in frames of their own; register them by multi-session "
                 "alignment and fuse on the aligned poses");
  demo->add_flag("--localize", o.localize,
                 "Teach and repeat: session 0's drifting odometry is the map; every later "
                 "session is localised against it and fused on its fused poses");
  demo->add_option("--vio-width", o.vio.width_px, "With --vio: grey camera width, px")
      ->capture_default_str();
  demo->add_option("--vio-height", o.vio.height_px, "With --vio: grey camera height, px")
      ->capture_default_str();
  demo->add_option("--vio-window", o.vio.window, "With --vio: keyframes in the VIO's window")
      ->capture_default_str();
  demo->add_option("--rest", o.rest_s,
                   "Seconds the camera stands still before each path (default: 1.5 with --vio, "
                   "0 without)");
  demo->add_flag(
      "--no-objects", [&o](std::int64_t) { o.objects = false; },
      "Skip the last step: the object database over the sessions' moved objects");
  demo->add_option("--device", o.device, "Vulkan device index or name substring");
  demo->add_flag("--quiet", o.quiet, "No progress bar");
  demo->add_flag("--incremental", o.incremental,
                 "Also select keyframes and fuse only those; about doubles the time");
  return demo;
}

int runDemo(const DemoOptions& o) {
  try {
    const DemoReport report = runDemoPipeline(o);
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

#include "occupancy_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <memory>

#include "strata/sim/sim_setup.h"
#include "strata/core/error.h"
#include "strata/occupancy/eval/occupancy_compare.h"
#include "json.h"
#include "machine_info.h"
#include "strata/sim/analytic_dataset.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata::bench {
namespace {

// Fixed scene constants so runs compare: the default 640 x 480 camera, 5 m range (the room's
// walls are within it), frames at 30 Hz along each scene's default trajectory.
constexpr float kMaxDepthM = 5.0f;
constexpr int kTruthPixelStride = 4;

eval::OccupancyComparisonSetup comparisonSetup(const OccupancyBenchOptions& o) {
  eval::OccupancyComparisonSetup s;
  s.map.voxel_size_m = o.voxel_size_m;
  s.map.max_depth_m = kMaxDepthM;
  s.map.validate();
  s.occupancy = OccupancyConfig::forMap(s.map);
  s.occupancy.pixel_stride = o.pixel_stride;
  s.occupancy.validate();
  s.frames = static_cast<std::size_t>(o.frames);
  s.truth_pixel_stride = kTruthPixelStride;
  s.run_reference = true;
  return s;
}

Json errorJson(const eval::SurfaceError& e) {
  return Json::object()
      .set("points", e.count)
      .set("mean_m", e.mean_m)
      .set("median_m", e.median_m)
      .set("p95_m", e.p95_m);
}

Json comparisonJson(const std::string& scene, const eval::OccupancyTsdfComparison& c) {
  const OccupancyAgreement& a = c.device_vs_reference;
  return Json::object()
      .set("scene", scene)
      .set("frames", c.frames)
      .set("occupancy_update_device_ms_per_frame", c.occupancy_device_ms)
      .set("occupancy_device_passes_ms_per_frame", Json::object()
                                                       .set("allocate", c.occupancy_allocate_ms)
                                                       .set("mark", c.occupancy_mark_ms)
                                                       .set("update", c.occupancy_update_ms))
      .set("frames_needing_exact_allocation", c.exact_fallbacks)
      .set("occupancy_update_reference_ms_per_frame", c.reference_ms)
      .set("tsdf_fusion_device_ms_per_frame", c.fusion_device_ms)
      .set("truth_points", c.truth_points)
      .set("occupancy", Json::object()
                            .set("occupied_voxels", c.occupied_voxels)
                            .set("free_voxels", c.free_voxels)
                            .set("surface_error", errorJson(c.occupancy_error))
                            .set("completeness", c.occupancy_completeness))
      .set("tsdf", Json::object()
                       .set("mesh_vertices", c.mesh_vertices)
                       .set("surface_error", errorJson(c.tsdf_error))
                       .set("completeness", c.tsdf_completeness))
      .set("device_vs_reference",
           Json::object()
               .set("voxels_compared", a.compared)
               .set("class_mismatches", a.class_mismatches)
               .set("log_odds_share_within_1e-5", a.shareWithin())
               .set("max_abs_log_odds_difference", a.max_abs_log_odds_difference));
}

Json occupancyNotes() {
  return Json::array()
      .push(
          "device times from Vulkan timestamp queries, frame 0 left out (buffers grow from "
          "empty); occupancy = depth upload + allocation + mark + update passes; TSDF fusion = "
          "upload + normals + allocation + integration; reference = C++ "
          "integrateOccupancyReference on one host thread (steady_clock)")
      .push(
          "surface_error: |exact signed distance| at occupied voxel centres / TSDF mesh "
          "vertices; completeness: share of true surface points (exact depth of the same "
          "frames, every 4th pixel from (1, 1), within the depth range;"
          " with pixel stride 1 these pixels also cast rays) within one voxel of an occupied "
          "voxel centre / of the TSDF mesh (point-to-triangle)")
      .push(
          "a voxel centre lies up to half a voxel diagonal from a surface it holds: the "
          "occupancy error floor is quantisation, the TSDF interpolates its zero crossing")
      .push(
          "on lavapipe the device is this CPU: device time is CPU time on LP_NUM_THREADS "
          "threads");
}

/// The analytic scene (exact depth) and the world's session 0 (noise on, no drift).
Json runScenes(vk::Context& context, const OccupancyBenchOptions& o, bool& ok) {
  eval::OccupancyComparisonSetup setup = comparisonSetup(o);
  if (!o.ply_dir.empty()) setup.ply_prefix = o.ply_dir + "/analytic_";
  sim::AnalyticDatasetConfig analytic_config;
  analytic_config.frame_count = o.frames;
  analytic_config.render_color = false;
  const sim::AnalyticDataset analytic(analytic_config);
  std::fprintf(stderr, "strata-bench occupancy: %s\n", analytic.name().c_str());
  const auto a = eval::compareOccupancyWithTsdf(
      context, analytic, [&](std::size_t i) { return analytic.load(i); },
      [&](const Eigen::Vector3d& p) { return analytic.scene().signedDistance(p); }, setup);

  const sim::SimSessionDataset session(sim::loadWorld(sim::findWorld(o.world), 0, 0), 0,
                                       sim::sessionConfig(30.0, o.frames, true, false));
  std::fprintf(stderr, "strata-bench occupancy: %s\n", session.name().c_str());
  if (!o.ply_dir.empty()) setup.ply_prefix = o.ply_dir + "/" + o.world + "_";
  const auto truth_frame = [&](std::size_t i) {
    RgbdFrame frame;
    frame.depth = session.render(i).depth_true;
    frame.T_W_C = session.truePoses()[i];
    return frame;
  };
  const auto s = eval::compareOccupancyWithTsdf(
      context, session, truth_frame,
      [&](const Eigen::Vector3d& p) {
        return static_cast<double>(session.scene().signedDistance(p.cast<float>()));
      },
      setup);
  ok = a.device_vs_reference.class_mismatches == 0 && s.device_vs_reference.class_mismatches == 0;
  return Json::array()
      .push(comparisonJson("analytic scene, exact depth", a))
      .push(comparisonJson("sim " + o.world + " session 0, sensor noise", s));
}

int runChecked(const OccupancyBenchOptions& o) {
  if (o.frames < 2) throw InputError("--frames must be at least 2 (frame 0 is not timed)");
  const eval::OccupancyComparisonSetup setup = comparisonSetup(o);  // validates early
  const std::string load_at_start = loadAverage();
  vk::ContextOptions options;
  options.device_selector = o.device;
  options.log_device = false;
  auto context = vk::Context::create(options);
  bool ok = false;
  Json results = runScenes(*context, o, ok);
  Json report = Json::object()
                    .set("benchmark", "occupancy")
                    .set("machine", machineInfo(context->deviceName(), load_at_start))
                    .set("settings", Json::object()
                                         .set("map_config", setup.map.describe())
                                         .set("occupancy_config", setup.occupancy.describe())
                                         .set("frames_per_scene", o.frames)
                                         .set("notes", occupancyNotes()))
                    .set("results", std::move(results))
                    .set("checks_passed", ok);
  emitReport(report, o.out_path);
  if (!ok) std::fprintf(stderr, "strata-bench occupancy: device and reference disagree\n");
  return ok ? 0 : 1;
}

}  // namespace

CLI::App* addOccupancyCommand(CLI::App& app, OccupancyBenchOptions& o) {
  CLI::App* cmd = app.add_subcommand("occupancy", "Occupancy layer vs TSDF (time, accuracy)");
  cmd->add_option("--world", o.world, "Simulated world (name or YAML)")->capture_default_str();
  cmd->add_option("--frames", o.frames, "Frames per scene")->capture_default_str();
  cmd->add_option("--voxel-size", o.voxel_size_m, "Voxel edge, metres")->capture_default_str();
  cmd->add_option("--pixel-stride", o.pixel_stride, "Every n-th pixel casts a ray")
      ->capture_default_str();
  cmd->add_option("--out", o.out_path, "Also write the JSON report here (atomically)");
  cmd->add_option("--ply", o.ply_dir, "Also write occupancy cubes and TSDF meshes here (PLY)");
  cmd->add_option("--device", o.device, "Vulkan device index or name substring");
  return cmd;
}

int runOccupancyBench(const OccupancyBenchOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench occupancy: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata-bench occupancy: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench occupancy: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

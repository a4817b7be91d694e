#include "plan_collision_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>

#include "strata/core/error.h"
#include "json.h"
#include "machine_info.h"
#include "strata/mapper/mapper.h"
#include "strata/plan/collision_checker.h"
#include "strata/plan/rrt_planner.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"
#include "bench_timing.h"

namespace strata::bench {
namespace {

constexpr std::uint32_t kSeed = 20261205;  // fixed: runs compare
const std::vector<std::size_t> kBatchSizes{1, 16, 256, 4096};
constexpr double kMinTimedMs = 200.0;  // each batch size repeats until this much host time

/// Known voxel centres where the robot's sphere is free (ESDF >= radius + a voxel, then the sphere
/// test under kOccupied, which also keeps unknown voxels out of reach), in a fixed order.
std::vector<Eigen::Vector3f> freeCentres(const EsdfMap& map, plan::CollisionChecker& checker,
                                         float radius_m) {
  std::vector<Eigen::Vector3f> candidates;
  for (const auto& [b, block] : map.blocks) {
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      // NOTE: a voxel centre barely clear of the radius passes the sphere test, but the test's
      // lower bound drops within the voxel: a robot there could not move. One voxel more.
      if (!esdfObserved(block[i]) || block[i].distance_m < radius_m + map.voxel_size_m) continue;
      const GlobalVoxelIndex v = b * kBlockEdge + Eigen::Vector3i(i % 8, (i / 8) % 8, i / 64);
      candidates.push_back(voxelCenter(v, map.voxel_size_m));
    }
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const Eigen::Vector3f& a, const Eigen::Vector3f& b) {
              return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
            });
  std::vector<EsdfSegment> points;  // zero-length capsules: the radius motions are checked with
  for (const Eigen::Vector3f& p : candidates) points.push_back({p, p});
  const std::vector<std::uint8_t> free =
      checker.segmentsFree(points, radius_m, UnknownPolicy::kOccupied);
  std::vector<Eigen::Vector3f> out;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    if (free[i] != 0) out.push_back(candidates[i]);
  }
  return out;
}

/// Segments between free centres about `length_m` apart (0.5 to 1.5 times): what a sampling
/// planner asks, some free, some through obstacles or unknown space.
std::vector<EsdfSegment> segmentsFrom(const std::vector<Eigen::Vector3f>& free, std::size_t n,
                                      float length_m, std::mt19937& rng) {
  std::vector<EsdfSegment> out;
  while (out.size() < n) {
    const Eigen::Vector3f a = free[rng() % free.size()];
    for (int attempt = 0; attempt < 1000; ++attempt) {
      const Eigen::Vector3f b = free[rng() % free.size()];
      const float d = (b - a).norm();
      if (d < 0.5f * length_m || d > 1.5f * length_m) continue;
      out.push_back({a, b});
      break;
    }
  }
  return out;
}

Json batchRow(plan::HostCollisionChecker& host, plan::DeviceCollisionChecker& device,
              const std::vector<EsdfSegment>& segments, float radius_m, bool& ok) {
  int repeats = 0;
  double host_ms = 0.0, device_wall_ms = 0.0;
  const double device_ms0 = device.deviceMs();
  const std::uint64_t spheres0 = host.spheresTested();
  std::size_t mismatches = 0, free_count = 0;
  while (host_ms < kMinTimedMs && repeats < 1000) {
    auto start = Clock::now();
    const auto on_host = host.segmentsFree(segments, radius_m, UnknownPolicy::kOccupied);
    host_ms += msSince(start);
    start = Clock::now();
    const auto on_device = device.segmentsFree(segments, radius_m, UnknownPolicy::kOccupied);
    device_wall_ms += msSince(start);
    for (std::size_t i = 0; i < segments.size(); ++i) {
      mismatches += on_host[i] != on_device[i] ? 1 : 0;
      free_count += repeats == 0 ? on_host[i] : 0;
    }
    ++repeats;
  }
  ok = ok && mismatches == 0;
  const double spheres = static_cast<double>(host.spheresTested() - spheres0) / repeats;
  return Json::object()
      .set("segments", segments.size())
      .set("spheres_per_batch", spheres)
      .set("free_segments", free_count)
      .set("repeats", repeats)
      .set("host_ms_per_batch", host_ms / repeats)
      .set("device_ms_per_batch", (device.deviceMs() - device_ms0) / repeats)
      .set("device_wall_ms_per_batch", device_wall_ms / repeats)
      .set("flag_mismatches", mismatches);
}

/// The free centre nearest to p.
Eigen::Vector3f nearestFree(const std::vector<Eigen::Vector3f>& free, const Eigen::Vector3f& p) {
  return *std::min_element(free.begin(), free.end(), [&](const auto& a, const auto& b) {
    return (a - p).squaredNorm() < (b - p).squaredNorm();
  });
}

/// Start and goal: the free centres nearest to the camera at the first fused frame and at the
/// fused frame farthest from it (observed free space the camera moved through, so a path likely
/// exists); false when their straight line is free (nothing to plan).
bool pickQuery(plan::CollisionChecker& checker, const std::vector<Eigen::Vector3f>& free,
               const Dataset& session, std::size_t frames, float radius_m,
               plan::PlanRequest* request) {
  const Eigen::Vector3f first = session.stamp(0).T_W_C.translation().cast<float>();
  Eigen::Vector3f farthest = first;
  for (std::size_t i = 1; i < frames; ++i) {
    const Eigen::Vector3f c = session.stamp(i).T_W_C.translation().cast<float>();
    if ((c - first).norm() > (farthest - first).norm()) farthest = c;
  }
  request->start_W = nearestFree(free, first);
  request->goal_W = nearestFree(free, farthest);
  return !checker.segmentFree(request->start_W, request->goal_W, radius_m,
                              UnknownPolicy::kOccupied);
}

Json rrtRow(plan::CollisionChecker& checker, const EsdfMap& map, const plan::PlanRequest& request,
            int iterations) {
  plan::RrtOptions options;
  options.bounds_W = plan::esdfBounds(map);
  options.max_iterations = static_cast<std::uint64_t>(iterations);
  plan::RrtPlanner planner(checker, options);
  const plan::PlanResult r = planner.plan(request);
  const plan::RrtStats& s = planner.lastStats();
  return Json::object()
      .set("success", r.success)
      .set("message", r.message)
      .set("planning_ms", r.planning_ms)
      .set("length_m", r.length_m)
      .set("length_before_shortening_m", s.shortened_from_m)
      .set("min_clearance_m", r.min_clearance_m)
      .set("iterations", s.iterations)
      .set("motions_checked", s.motions_checked)
      .set("sphere_tests", r.collision_checks)
      .set("batches", s.batches)
      .set("device_ms", s.device_ms);
}

Json collisionNotes() {
  return Json::array()
      .push(
          "segments: capsules of the robot radius from free known voxel centres (ESDF >= radius), "
          "random directions, fixed seed; UnknownPolicy::kOccupied")
      .push(
          "host: HostCollisionChecker (EsdfQuery on the downloaded ESDF, one thread); device: "
          "DeviceCollisionChecker, one dispatch per batch; device_ms from timestamp queries, "
          "device_wall_ms with the copies and the submission")
      .push(
          "rrt: informed RRT* on OMPL, capped iterations and a fixed seed; OMPL asks one motion "
          "at a time, so batches ~ motions (one dispatch each on the device)")
      .push(
          "on lavapipe the device is this CPU: device time is CPU time on LP_NUM_THREADS threads");
}

int runChecked(const PlanCollisionBenchOptions& o) {
  if (o.frames < 1) throw InputError("--frames must be >= 1");
  if (!(o.radius_m > 0.0f) || !(o.segment_length_m > 0.0f)) {
    throw InputError("--radius and --segment-length must be > 0");
  }
  const std::string load_at_start = loadAverage();
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  context_options.log_device = false;
  auto context = vk::Context::create(context_options);
  MapperConfig config;
  config.map.voxel_size_m = o.voxel_size_m;
  config.map.allocate_free_space = true;
  config.esdf = true;
  Mapper mapper(config, *context);
  auto world = std::make_shared<const sim::World>(sim::World::load(sim::findWorld(o.world)));
  const sim::SimSessionDataset session(world, 0);
  const std::size_t frames = std::min<std::size_t>(session.size(), o.frames);
  std::fprintf(stderr, "strata-bench plan-collision: fusing %zu frames of %s\n", frames,
               session.name().c_str());
  for (std::size_t i = 0; i < frames; ++i) mapper.integrate(session.load(i), session.intrinsics());
  mapper.updateEsdf();
  const EsdfMap& map = mapper.esdf();
  plan::HostCollisionChecker host(map);
  plan::DeviceCollisionChecker device(*context, *mapper.deviceEsdf());
  const std::vector<Eigen::Vector3f> free = freeCentres(map, host, o.radius_m);
  if (free.empty()) throw InputError("the map has no free known voxel for the robot radius");
  std::mt19937 rng(kSeed);
  bool ok = true;
  device.segmentsFree(segmentsFrom(free, 16, o.segment_length_m, rng), o.radius_m,
                      UnknownPolicy::kOccupied);  // warm-up: lavapipe compiles on first use
  Json batches = Json::array();
  for (const std::size_t n : kBatchSizes) {
    std::fprintf(stderr, "strata-bench plan-collision: batches of %zu segments\n", n);
    batches.push(
        batchRow(host, device, segmentsFrom(free, n, o.segment_length_m, rng), o.radius_m, ok));
  }
  plan::PlanRequest request;
  request.radius_m = o.radius_m;
  request.time_budget_s = 120.0;
  request.seed = kSeed;
  Json rrt = Json("the straight line from start to goal is free: no RRT* query");
  if (pickQuery(host, free, session, frames, o.radius_m, &request)) {
    std::fprintf(stderr, "strata-bench plan-collision: RRT* on the host and on the device\n");
    const Json on_host = rrtRow(host, map, request, o.rrt_iterations);
    const Json on_device = rrtRow(device, map, request, o.rrt_iterations);
    rrt = Json::object();
    rrt.set("start_W",
            Json::numbers({request.start_W.x(), request.start_W.y(), request.start_W.z()}))
        .set("goal_W", Json::numbers({request.goal_W.x(), request.goal_W.y(), request.goal_W.z()}))
        .set("host", on_host)
        .set("device", on_device);
  }
  Json report =
      Json::object()
          .set("benchmark", "plan-collision")
          .set("machine", machineInfo(context->deviceName(), load_at_start))
          .set("settings", Json::object()
                               .set("world", o.world)
                               .set("frames", frames)
                               .set("voxel_size_m", static_cast<double>(o.voxel_size_m))
                               .set("radius_m", static_cast<double>(o.radius_m))
                               .set("segment_length_m", static_cast<double>(o.segment_length_m))
                               .set("rrt_iterations", o.rrt_iterations)
                               .set("notes", collisionNotes()))
          .set("map",
               Json::object().set("blocks", map.blocks.size()).set("free_centres", free.size()))
          .set("segment_batches", batches)
          .set("rrt", rrt)
          .set("checks_passed", ok);
  emitReport(report, o.out_path);
  if (!ok) std::fprintf(stderr, "strata-bench plan-collision: host and device flags differ\n");
  return ok ? 0 : 1;
}

}  // namespace

CLI::App* addPlanCollisionCommand(CLI::App& app, PlanCollisionBenchOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "plan-collision", "Batched capsule checks, host vs device, and an RRT* query with each");
  cmd->add_option("--world", o.world, "Simulated world (name or YAML)")->capture_default_str();
  cmd->add_option("--frames", o.frames, "Frames of session 0 fused")->capture_default_str();
  cmd->add_option("--voxel-size", o.voxel_size_m, "Voxel edge, metres")->capture_default_str();
  cmd->add_option("--radius", o.radius_m, "Robot radius, metres")->capture_default_str();
  cmd->add_option("--segment-length", o.segment_length_m, "Segment length, metres")
      ->capture_default_str();
  cmd->add_option("--rrt-iterations", o.rrt_iterations, "RRT* iteration cap")
      ->capture_default_str();
  cmd->add_option("--out", o.out_path, "Also write the JSON report here (atomically)");
  cmd->add_option("--device", o.device, "Vulkan device index or name substring");
  return cmd;
}

int runPlanCollisionBench(const PlanCollisionBenchOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench plan-collision: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata-bench plan-collision: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench plan-collision: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

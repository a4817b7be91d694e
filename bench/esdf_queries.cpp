#include "esdf_queries.h"

#include <chrono>
#include <cmath>
#include <map>
#include <random>
#include <thread>

#include "cli/esdf_slice.h"
#include "esdf_runs.h"
#include "strata/esdf/esdf_query.h"
#include "strata/esdf/esdf_query_kernel.h"
#include "bench_timing.h"

namespace strata::bench {
namespace {

constexpr std::uint32_t kSeed = 20261122;  // fixed: runs compare
constexpr float kSegmentLengthM = 0.5f;
constexpr std::size_t kSegmentsPerPoint = 10;  // one segment per 10 points

/// Half jittered around observed voxels (where planners ask), half uniform in the blocks' box.
std::vector<Eigen::Vector3f> queryPoints(const EsdfMap& map, std::size_t count) {
  std::vector<Eigen::Vector3f> observed;
  Eigen::Vector3i lo = Eigen::Vector3i::Constant(1 << 30), hi = -lo;
  for (const auto& [b, block] : map.blocks) {
    lo = lo.cwiseMin(b);
    hi = hi.cwiseMax(b);
    for (int i = 0; i < kVoxelsPerBlock; i += 7) {
      if (!esdfObserved(block[i])) continue;
      const GlobalVoxelIndex v = b * kBlockEdge + Eigen::Vector3i(i % 8, (i / 8) % 8, i / 64);
      observed.push_back(voxelCenter(v, map.voxel_size_m));
    }
  }
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Eigen::Vector3f> points;
  if (observed.empty()) return points;
  const Eigen::Vector3f box_lo = lo.cast<float>() * map.voxel_size_m * kBlockEdge;
  const Eigen::Vector3f box_size =
      (hi - lo + Eigen::Vector3i::Ones()).cast<float>() * map.voxel_size_m * kBlockEdge;
  for (std::size_t i = 0; i < count; ++i) {
    // One draw each, z first: the order of f(u(rng), u(rng)) is open in C++ (gcc and clang differ).
    const float z = u(rng), y = u(rng), x = u(rng);
    const Eigen::Vector3f t(x, y, z);
    if (i % 2 == 0) {
      points.push_back(box_lo + t.cwiseProduct(box_size));
    } else {
      const Eigen::Vector3f jitter =
          (t - Eigen::Vector3f::Constant(0.5f)) * 4.0f * map.voxel_size_m;
      points.push_back(observed[rng() % observed.size()] + jitter);
    }
  }
  return points;
}

Json rate(std::size_t items, double ms) {
  return Json::object().set("ms", ms).set("per_s", ms > 0.0 ? items / (ms / 1000.0) : 0.0);
}

Json hostQueries(const EsdfQuery& query, const std::vector<Eigen::Vector3f>& points,
                 const EsdfBenchSettings& s) {
  auto start = Clock::now();
  query.sample(points);
  const double sample_ms = msSince(start);
  start = Clock::now();
  query.isSphereFree(points, s.query_radius_m, s.query_margin_m, UnknownPolicy::kOccupied);
  const double occupied_ms = msSince(start);
  start = Clock::now();
  query.isSphereFree(points, s.query_radius_m, s.query_margin_m, UnknownPolicy::kFree);
  const double free_ms = msSince(start);
  std::vector<EsdfSegment> segments;
  for (std::size_t i = 0; i < points.size(); i += kSegmentsPerPoint) {
    segments.push_back({points[i], points[i] + Eigen::Vector3f(kSegmentLengthM, 0.0f, 0.0f)});
  }
  start = Clock::now();
  query.isSegmentFree(segments, s.query_radius_m, UnknownPolicy::kOccupied);
  const double segment_ms = msSince(start);
  return Json::object()
      .set("threads", static_cast<int>(std::thread::hardware_concurrency()))
      .set("sample", rate(points.size(), sample_ms))
      .set("sphere_unknown_occupied", rate(points.size(), occupied_ms))
      .set("sphere_unknown_free", rate(points.size(), free_ms))
      .set("segments_0_5m_unknown_occupied", rate(segments.size(), segment_ms));
}

/// Counts of device answers that differ from the host's.
Json agreement(const EsdfQuery& host, const std::vector<Eigen::Vector3f>& points,
               const EsdfQueryResult& device, const EsdfBenchSettings& s, bool& ok) {
  const std::vector<EsdfSample> expected = host.sample(points);
  const std::vector<std::uint8_t> free =
      host.isSphereFree(points, s.query_radius_m, s.query_margin_m, UnknownPolicy::kOccupied);
  std::size_t samples = 0, flags = 0, free_count = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const EsdfSample &d = device.samples[i], &h = expected[i];
    samples += d.status != h.status || std::fabs(d.distance_m - h.distance_m) > 1e-4f ? 1 : 0;
    flags += free[i] != device.sphere_free[i] ? 1 : 0;
    free_count += free[i];
  }
  // NOTE: a point on a voxel face or a clearance equal to the radius may round either way.
  ok = ok && samples <= points.size() / 1000 && flags <= points.size() / 1000;
  return Json::object()
      .set("sample_mismatches", samples)
      .set("sphere_flag_mismatches", flags)
      .set("free_spheres_host", free_count);
}

}  // namespace

Json benchQueries(vk::Context& context, DeviceEsdf& esdf, const EsdfMap& map,
                  const EsdfBenchSettings& s, bool& ok) {
  const std::vector<Eigen::Vector3f> points = queryPoints(map, s.query_points);
  if (points.empty()) return Json("no observed voxel to query");
  const EsdfQuery host(map);
  EsdfQueryKernel kernel(context);
  const EsdfSphereTest spheres{s.query_radius_m, s.query_margin_m, UnknownPolicy::kOccupied};
  kernel.run(esdf, points, spheres);  // warm-up: lavapipe compiles on the first dispatch
  auto start = Clock::now();
  const EsdfQueryResult samples_only = kernel.run(esdf, points);
  const double samples_wall_ms = msSince(start);
  start = Clock::now();
  const EsdfQueryResult with_spheres = kernel.run(esdf, points, spheres);
  const double spheres_wall_ms = msSince(start);
  Json device =
      Json::object()
          .set("sample_device", rate(points.size(), samples_only.device_ms))
          .set("sample_wall_with_copies", rate(points.size(), samples_wall_ms))
          .set("sample_and_sphere_unknown_occupied_device",
               rate(points.size(), with_spheres.device_ms))
          .set("sample_and_sphere_wall_with_copies", rate(points.size(), spheres_wall_ms));
  return Json::object()
      .set("points", points.size())
      .set("sphere_radius_m", static_cast<double>(s.query_radius_m))
      .set("sphere_margin_m", static_cast<double>(s.query_margin_m))
      .set("host", hostQueries(host, points, s))
      .set("device", device)
      .set("device_vs_host", agreement(host, points, with_spheres, s, ok));
}

Json benchSlice(const EsdfMap& map) {
  std::map<int, int> blocks_per_layer;
  for (const auto& [b, block] : map.blocks) ++blocks_per_layer[b.z()];
  if (blocks_per_layer.empty()) return Json("empty map");
  const auto layer =
      std::max_element(blocks_per_layer.begin(), blocks_per_layer.end(),
                       [](const auto& a, const auto& b) { return a.second < b.second; });
  apps::EsdfSliceOptions options;
  options.z_m = (static_cast<float>(layer->first * kBlockEdge) + 4.5f) * map.voxel_size_m;
  options.max_distance_m = map.config.max_distance_m;
  const auto start = Clock::now();
  const apps::EsdfSlice slice = apps::renderEsdfSlice(map, options);
  const double ms = msSince(start);
  return Json::object()
      .set("z_m", static_cast<double>(options.z_m))
      .set("render_ms", ms)
      .set("voxels", slice.stats.width_voxels * slice.stats.height_voxels)
      .set("image_px",
           std::to_string(slice.image.width_px) + "x" + std::to_string(slice.image.height_px));
}

}  // namespace strata::bench

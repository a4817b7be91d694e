// Occupancy layer: the log-odds rule (Hornung et al. 2013, Eq. 2-3) on the reference and
// the device, and the device against the reference voxel for voxel on the analytic scene and a
// simulated room session.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <tuple>

#include "strata/core/error.h"
#include "fusion_fixture.h"
#include "strata/integrate/device_fusion.h"
#include "strata/occupancy/occupancy_device.h"
#include "strata/occupancy/occupancy_reference.h"
#include "strata/sim/analytic_dataset.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata {
namespace {

constexpr float kVoxelM = 0.1f;
// Both sides add the same float log-odds in the same order: any difference is a bug, but allow
// rounding should a driver contract a product into an FMA somewhere.
constexpr float kLogOddsTolerance = 1e-5f;

MapConfig mapConfig(float voxel_m) {
  MapConfig config;
  config.voxel_size_m = voxel_m;
  config.max_depth_m = 6.0f;
  // Small starting capacities: the layers must survive the pool growing and the table rehashing.
  config.initial_block_capacity = 64;
  config.initial_hash_capacity = 64;
  return config;
}

CameraIntrinsics smallCamera() {  // a quarter of the default 640 x 480 camera: tests stay fast
  CameraIntrinsics in;
  in.width_px = 160;
  in.height_px = 120;
  in.fx_px = in.fy_px = 131.25f;
  in.cx_px = 79.5f;
  in.cy_px = 59.5f;
  return in;
}

/// A camera at the origin looking along +z at a wall `depth_m` away (every pixel).
RgbdFrame wallFrame(const CameraIntrinsics& in, float depth_m) {
  RgbdFrame frame;
  frame.depth = DepthImage(in.width_px, in.height_px, depth_m);
  frame.T_W_C.translation() = Eigen::Vector3d(0.013, -0.021, 0.007);  // off the voxel grid
  return frame;
}

/// The same frames into the device layer (over a fusion's map) and into the reference.
class Scans {
 public:
  Scans(const OccupancyConfig& config, float voxel_m)
      : fusion_(test::sharedContext(), mapConfig(voxel_m)),
        occupancy_(fusion_.map(), config),
        reference_(voxel_m) {}

  void add(const RgbdFrame& frame, const CameraIntrinsics& in) {
    const OccupancyFrameStats stats = occupancy_.integrate(frame, in);
    max_allocation_passes_ = std::max(max_allocation_passes_, stats.allocation_passes);
    integrateOccupancyReference(frame.depth, FrameCamera::from(in, frame.T_W_C),
                                occupancy_.config(), reference_);
  }
  OccupancyMap device() {
    OccupancyMap out(fusion_.config().voxel_size_m);
    occupancy_.download(out);
    return out;
  }
  const OccupancyMap& reference() const { return reference_; }
  DeviceOccupancy& occupancy() { return occupancy_; }
  std::uint32_t maxAllocationPasses() const { return max_allocation_passes_; }

 private:
  DeviceFusion fusion_;
  DeviceOccupancy occupancy_;
  OccupancyMap reference_;
  std::uint32_t max_allocation_passes_ = 0;
};

/// `expect_surface`: the scans saw a surface within range (some voxel occupied).
void expectDeviceEqualsReference(Scans& scans, const std::string& what,
                                 bool expect_surface = true) {
  const OccupancyMap device = scans.device();
  const OccupancyLogOdds l = scans.occupancy().config().logOdds();
  const OccupancyAgreement agreement =
      compareOccupancy(device, scans.reference(), l, kLogOddsTolerance);
  const OccupancyCounts counts = countOccupancy(scans.reference(), l);
  std::printf("[ occupancy ] %s: %llu compared, %llu occupied, %llu free, max |dl| %.3g\n",
              what.c_str(), static_cast<unsigned long long>(agreement.compared),
              static_cast<unsigned long long>(counts.occupied),
              static_cast<unsigned long long>(counts.free), agreement.max_abs_log_odds_difference);
  EXPECT_EQ(counts.occupied > 0, expect_surface) << what;
  EXPECT_GT(counts.free, counts.occupied) << what;  // rays cross more voxels than they end in
  EXPECT_EQ(agreement.class_mismatches, 0u) << what;
  EXPECT_GE(agreement.shareWithin(), 0.999) << what;
  EXPECT_EQ(device.blockCount(), scans.reference().blockCount()) << what;
}

/// Global voxel of pixel (u, v)'s endpoint at `depth_m` (the kernels' own arithmetic).
GlobalVoxelIndex endpointVoxel(const RgbdFrame& frame, const CameraIntrinsics& in, float u, float v,
                               float depth_m, const OccupancyConfig& config) {
  OccupancyRayEnds ends;
  // A negative depth names the point that far behind the camera, mirrored through its centre
  // (occupancyRayEnds refuses such a sample and leaves `ends` unset: reading it anyway gave a
  // different voxel with each compiler).
  const bool valid =
      occupancyRayEnds(u, v, std::fabs(depth_m),
                       occupancyRayCamera(FrameCamera::from(in, frame.T_W_C), config, kVoxelM), ends);
  EXPECT_TRUE(valid) << "depth " << depth_m;
  const Eigen::Vector3f end_vox =
      depth_m >= 0.0f ? ends.end_vox : Eigen::Vector3f(2.0f * ends.origin_vox - ends.end_vox);
  return end_vox.array().floor().cast<int>().matrix();
}

/// Class and log-odds of `voxel` on both sides; they must agree.
std::pair<OccupancyClass, float> probe(Scans& scans, const GlobalVoxelIndex& voxel) {
  const OccupancyLogOdds l = scans.occupancy().config().logOdds();
  const OccupancyMap device = scans.device();
  const OccupancyClass c = scans.reference().classify(voxel, l);
  EXPECT_EQ(device.classify(voxel, l), c);
  const OccupancyVoxel* d = device.findVoxel(voxel);
  const OccupancyVoxel* r = scans.reference().findVoxel(voxel);
  if (d == nullptr || r == nullptr || c == OccupancyClass::kUnknown) return {c, 0.0f};
  EXPECT_EQ(d->log_odds, r->log_odds);
  return {c, r->log_odds};
}

TEST(Occupancy, VoxelSeenFreeThenOccupiedFollowsTheLogOddsRule) {
  const CameraIntrinsics in = smallCamera();
  OccupancyConfig config;
  config.pixel_stride = 4;
  Scans scans(config, kVoxelM);
  const OccupancyLogOdds l = config.logOdds();
  const RgbdFrame far_wall = wallFrame(in, 3.0f), near_wall = wallFrame(in, 1.5f);
  const GlobalVoxelIndex voxel = endpointVoxel(near_wall, in, 80, 60, 1.5f, config);
  const GlobalVoxelIndex behind = endpointVoxel(far_wall, in, 80, 60, 3.5f, config);
  const GlobalVoxelIndex behind_camera = endpointVoxel(far_wall, in, 80, 60, -1.0f, config);

  scans.add(far_wall, in);  // the ray of pixel (80, 60) passes through `voxel`: one miss
  EXPECT_EQ(probe(scans, voxel), std::make_pair(OccupancyClass::kFree, l.miss));
  scans.add(near_wall, in);  // now it ends there: Eq. (2), L = l_miss + l_hit
  const float after_hit = l.miss + l.hit;
  EXPECT_EQ(probe(scans, voxel), std::make_pair(OccupancyClass::kOccupied, after_hit));
  scans.add(far_wall, in);  // one miss leaves it just occupied (0.44 - 0.41 > 0) ...
  EXPECT_EQ(probe(scans, voxel), std::make_pair(OccupancyClass::kOccupied, after_hit + l.miss));
  scans.add(far_wall, in);  // ... a second frees it
  EXPECT_EQ(probe(scans, voxel).first, OccupancyClass::kFree);
  // Never reached by a ray: unknown, whatever was seen around it.
  EXPECT_EQ(probe(scans, behind).first, OccupancyClass::kUnknown);
  EXPECT_EQ(probe(scans, behind_camera).first, OccupancyClass::kUnknown);
}

TEST(Occupancy, ClampingBoundsConfidenceSoAWallCanBeCleared) {
  const CameraIntrinsics in = smallCamera();
  OccupancyConfig config;
  config.pixel_stride = 4;
  Scans scans(config, kVoxelM);
  const OccupancyLogOdds l = config.logOdds();
  const RgbdFrame far_wall = wallFrame(in, 3.0f), near_wall = wallFrame(in, 1.5f);
  const GlobalVoxelIndex wall = endpointVoxel(near_wall, in, 80, 60, 1.5f, config);
  const GlobalVoxelIndex front = endpointVoxel(near_wall, in, 80, 60, 0.75f, config);
  for (int i = 0; i < 10; ++i) scans.add(near_wall, in);  // 10 x 0.85 would be 8.5 unclamped
  EXPECT_EQ(probe(scans, wall), std::make_pair(OccupancyClass::kOccupied, l.max));
  EXPECT_EQ(probe(scans, front), std::make_pair(OccupancyClass::kFree, l.min));
  for (const auto& [index, block] : scans.reference().blocks()) {
    for (const OccupancyVoxel& v : block) {
      ASSERT_TRUE(v.state == 0u || (v.log_odds >= l.min && v.log_odds <= l.max));
    }
  }
  // The wall moved away: from l_max, ceil(l_max / -l_miss) misses clear it (9 with the defaults).
  const int misses_needed = static_cast<int>(std::ceil((l.max - l.occupied) / -l.miss));
  int misses = 0;
  while (probe(scans, wall).first == OccupancyClass::kOccupied && misses < 20) {
    scans.add(far_wall, in);
    ++misses;
  }
  EXPECT_EQ(misses, misses_needed);
  expectDeviceEqualsReference(scans, "wall scans");
}

TEST(Occupancy, MissingSamplesCastNoRayAndSamplesBeyondRangeOnlyClear) {
  const CameraIntrinsics in = smallCamera();
  OccupancyConfig config;
  config.min_depth_m = 0.0f;  // 0 still marks a missing sample
  // Rays are cut at z = 1.657 m in the world, in voxel 16: the first of a block, which only the
  // cut ends reach (and they update nothing there).
  config.max_range_m = 1.65f;
  config.pixel_stride = 4;
  Scans scans(config, kVoxelM);
  RgbdFrame missing = wallFrame(in, 0.0f);
  missing.depth.at(8, 8) = std::nanf("");
  missing.depth.at(12, 8) = std::numeric_limits<float>::infinity();
  scans.add(missing, in);
  EXPECT_EQ(scans.device().blockCount(), 0u);
  EXPECT_EQ(scans.reference().blockCount(), 0u);

  const RgbdFrame far_wall = wallFrame(in, 3.0f);  // beyond max range: free up to it, no hit
  scans.add(far_wall, in);
  const OccupancyLogOdds l = config.logOdds();
  EXPECT_EQ(countOccupancy(scans.device(), l).occupied, 0u);
  EXPECT_EQ(probe(scans, endpointVoxel(far_wall, in, 80, 60, 1.55f, config)).first,
            OccupancyClass::kFree);
  EXPECT_EQ(probe(scans, endpointVoxel(far_wall, in, 80, 60, 2.5f, config)).first,
            OccupancyClass::kUnknown);
  EXPECT_EQ(probe(scans, endpointVoxel(far_wall, in, 80, 60, 3.0f, config)).first,
            OccupancyClass::kUnknown);
  expectDeviceEqualsReference(scans, "beyond max range", false);
  // The exact voxel walk allocates no block for a cut ray's end voxel, and marking needs none.
  Scans exact(config, kVoxelM);
  exact.occupancy().setExactAllocation(true);
  exact.add(far_wall, in);
  exact.add(wallFrame(in, 1.5f), in);
  scans.add(wallFrame(in, 1.5f), in);
  const OccupancyAgreement agreement = compareOccupancy(exact.device(), scans.device(), l, 0.0f);
  EXPECT_EQ(agreement.class_mismatches, 0u);
  EXPECT_EQ(agreement.log_odds_within, agreement.compared);
}

/// Voxels that some ray of `frame` passes through and voxels where one ends (kernels' traversal).
void rayVoxelSets(const RgbdFrame& frame, const CameraIntrinsics& in, const OccupancyConfig& config,
                  float voxel_m, std::set<std::tuple<int, int, int>>& passed,
                  std::set<std::tuple<int, int, int>>& ended) {
  const OccupancyRayCamera c =
      occupancyRayCamera(FrameCamera::from(in, frame.T_W_C), config, voxel_m);
  for (int v = 0; v < in.height_px; v += config.pixel_stride) {
    for (int u = 0; u < in.width_px; u += config.pixel_stride) {
      OccupancyRayEnds ends;
      if (!occupancyRayEnds(u, v, frame.depth.at(u, v), c, ends)) continue;
      OccupancyVoxelRay ray(ends);
      for (; !ray.atEnd(); ray.advance()) {
        passed.emplace(ray.voxel().x(), ray.voxel().y(), ray.voxel().z());
      }
      if (ends.hit) ended.emplace(ray.voxel().x(), ray.voxel().y(), ray.voxel().z());
    }
  }
}

TEST(Occupancy, OneUpdatePerVoxelPerScanHitOverMiss) {
  sim::AnalyticDatasetConfig data;
  data.frame_count = 4;
  data.intrinsics = smallCamera();
  data.render_color = false;
  const sim::AnalyticDataset dataset(data);
  const RgbdFrame frame = dataset.load(1);
  OccupancyConfig config = OccupancyConfig::forMap(mapConfig(kVoxelM));
  Scans scans(config, kVoxelM);
  scans.add(frame, dataset.intrinsics());
  std::set<std::tuple<int, int, int>> passed, ended;
  rayVoxelSets(frame, dataset.intrinsics(), config, kVoxelM, passed, ended);
  const OccupancyLogOdds l = config.logOdds();
  const OccupancyMap device = scans.device();
  std::size_t both = 0;
  for (const auto& [x, y, z] : passed) {
    const OccupancyVoxel* v = device.findVoxel(GlobalVoxelIndex(x, y, z));
    ASSERT_NE(v, nullptr);
    // Many rays cross a voxel near the camera, yet it took one miss; ends win over passes.
    EXPECT_EQ(v->log_odds, ended.count({x, y, z}) > 0 ? l.hit : l.miss);
    both += ended.count({x, y, z});
  }
  for (const auto& [x, y, z] : ended) {
    ASSERT_NE(device.findVoxel(GlobalVoxelIndex(x, y, z)), nullptr);
    EXPECT_EQ(device.findVoxel(GlobalVoxelIndex(x, y, z))->log_odds, l.hit);
  }
  EXPECT_GT(both, 0u) << "the scene should have voxels both crossed and hit in one scan";
  const OccupancyCounts counts = countOccupancy(device, l);
  EXPECT_EQ(counts.occupied, ended.size());
  EXPECT_EQ(counts.free + counts.occupied, passed.size() + ended.size() - both);
}

TEST(Occupancy, DeviceEqualsReferenceOnAnalyticScene) {
  sim::AnalyticDatasetConfig data;
  data.frame_count = 8;
  data.intrinsics = smallCamera();
  data.render_color = false;
  const sim::AnalyticDataset dataset(data);
  for (const float voxel_m : {0.1f, 0.05f}) {
    Scans scans(OccupancyConfig::forMap(mapConfig(voxel_m)), voxel_m);
    for (std::size_t i = 0; i < dataset.size(); ++i)
      scans.add(dataset.load(i), dataset.intrinsics());
    expectDeviceEqualsReference(scans, "analytic scene at " + std::to_string(voxel_m) + " m");
    EXPECT_GT(scans.maxAllocationPasses(), 1u) << "the 64-entry table should have had to grow";
  }
}

TEST(Occupancy, BlockWalkAllocationGivesTheLayerOfTheExactVoxelWalk) {
  sim::AnalyticDatasetConfig data;
  data.frame_count = 6;
  data.intrinsics = smallCamera();
  data.render_color = false;
  const sim::AnalyticDataset dataset(data);
  Scans block_walk(OccupancyConfig::forMap(mapConfig(0.05f)), 0.05f);
  Scans voxel_walk(OccupancyConfig::forMap(mapConfig(0.05f)), 0.05f);
  voxel_walk.occupancy().setExactAllocation(true);
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    block_walk.add(dataset.load(i), dataset.intrinsics());
    voxel_walk.add(dataset.load(i), dataset.intrinsics());
  }
  expectDeviceEqualsReference(voxel_walk, "analytic scene, exact allocation");
  const OccupancyAgreement agreement = compareOccupancy(
      block_walk.device(), voxel_walk.device(), block_walk.occupancy().config().logOdds(), 0.0f);
  EXPECT_EQ(agreement.class_mismatches, 0u);
  EXPECT_EQ(agreement.log_odds_within, agreement.compared);
}

TEST(Occupancy, DeviceEqualsReferenceOnSimulatedRoomWithNoise) {
  sim::SimSessionConfig session_config;
  session_config.max_frames = 8;  // noise on (the camera's default)
  session_config.camera.intrinsics = smallCamera();
  const sim::SimSessionDataset session(
      std::make_shared<const sim::World>(sim::World::load(sim::findWorld("room"))), 0,
      session_config);
  OccupancyConfig config = OccupancyConfig::forMap(mapConfig(0.05f));
  config.pixel_stride = 2;
  Scans scans(config, 0.05f);
  for (std::size_t i = 0; i < session.size(); ++i) scans.add(session.load(i), session.intrinsics());
  expectDeviceEqualsReference(scans, "room session 0, stride 2");
}

}  // namespace
}  // namespace strata

// ESDF: the device's exact transform against the C++ reference and against a brute-force distance
// transform written here, on the analytic scene and a simulated room; incremental equals batch
// while an object appears and disappears; signs; the empty map; slabs when the box is too large.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>

#include "fusion_fixture.h"
#include "strata/esdf/esdf.h"
#include "strata/esdf/esdf_compare.h"
#include "strata/sim/analytic_dataset.h"
#include "strata/sim/default_scene.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata {
namespace {

struct EsdfDiff {
  std::uint64_t compared = 0, over_voxel = 0, flag_mismatches = 0;
  double sum_abs_voxels = 0.0;
  double share() const { return compared ? static_cast<double>(over_voxel) / compared : 0.0; }
  double mean() const { return compared ? sum_abs_voxels / compared : 0.0; }
  void add(float a_m, float b_m, float voxel_m) {
    const double e = std::fabs(a_m - b_m) / voxel_m;
    ++compared;
    sum_abs_voxels += e;
    if (e > 1.0) ++over_voxel;
  }
};

void expectWithinTolerance(const EsdfDiff& d, const std::string& what) {
  EXPECT_GT(d.compared, 1000u) << what;
  EXPECT_LE(d.share(), kEsdfMaxShareOverVoxel)
      << what << ": " << d.over_voxel << " of " << d.compared;
  EXPECT_LT(d.mean(), kEsdfMaxMeanErrorVoxels) << what;
  EXPECT_EQ(d.flag_mismatches, 0u) << what;
}

/// Every observed voxel of `expected` within the max distance (it has a site), against `actual`.
EsdfDiff compareEsdf(const EsdfMap& actual, const EsdfMap& expected) {
  EsdfDiff d;
  EXPECT_EQ(actual.blocks.size(), expected.blocks.size());
  for (const auto& [b, block] : expected.blocks) {
    const auto it = actual.blocks.find(b);
    if (it == actual.blocks.end()) continue;
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const EsdfVoxel &e = block[i], &a = it->second[i];
      if (esdfObserved(e) != esdfObserved(a)) ++d.flag_mismatches;
      if (esdfObserved(e) && esdfHasSite(e)) d.add(a.distance_m, e.distance_m, actual.voxel_size_m);
    }
  }
  return d;
}

GlobalVoxelIndex voxelOf(const BlockIndex& b, int i) {
  return b * kBlockEdge + GlobalVoxelIndex(i % 8, (i / 8) % 8, i / 64);
}

/// Brute force over every site of the map, on every `stride`-th observed voxel of `esdf`.
EsdfDiff compareBruteForce(const EsdfMap& esdf, const TsdfMap& tsdf, int stride) {
  const float voxel = tsdf.config().voxel_size_m;
  const EsdfConfig& c = esdf.config;
  std::vector<GlobalVoxelIndex> sites;
  for (const auto& [b, block] : tsdf.blocks()) {
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      if (block[i].weight >= c.min_weight &&
          std::fabs(block[i].tsdf_m) <= c.site_threshold_voxels * voxel) {
        sites.push_back(voxelOf(b, i));
      }
    }
  }
  EsdfDiff d;
  int counter = 0;
  for (const auto& [b, block] : tsdf.blocks()) {
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      if (block[i].weight < c.min_weight || ++counter % stride != 0) continue;
      const GlobalVoxelIndex v = voxelOf(b, i);
      std::int64_t best = std::numeric_limits<std::int64_t>::max();
      for (const GlobalVoxelIndex& s : sites)
        best = std::min<std::int64_t>(best, (s - v).squaredNorm());
      const double dist = std::sqrt(static_cast<double>(best)) * voxel;
      if (dist > c.max_distance_m) continue;
      const float expected = static_cast<float>(block[i].tsdf_m < 0.0f ? -dist : dist);
      d.add(esdf.findVoxel(v)->distance_m, expected, voxel);
    }
  }
  return d;
}

/// Observed voxels inside (true SDF < -1 voxel) must be negative; free voxels beyond the
/// truncation band positive (nearer ones may lie in the band behind a thin wall: negative TSDF).
template <typename Sdf>
void expectSigns(const EsdfMap& esdf, float truncation_m, Sdf&& true_sdf) {
  std::uint64_t inside = 0, free = 0, wrong = 0;
  for (const auto& [b, block] : esdf.blocks) {
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      // Sites (distance 0) lie on the surface: no sign to check.
      if (!esdfObserved(block[i]) || block[i].distance_m == 0.0f) continue;
      const float sdf = true_sdf(voxelCenter(voxelOf(b, i), esdf.voxel_size_m));
      if (sdf > -esdf.voxel_size_m && sdf < truncation_m + esdf.voxel_size_m) continue;
      ++(sdf < 0.0f ? inside : free);
      if ((sdf < 0.0f) != (block[i].distance_m < 0.0f)) ++wrong;
    }
  }
  EXPECT_GT(inside, 0u);
  EXPECT_GT(free, 500u);
  EXPECT_LE(wrong, (inside + free) / 1000)
      << wrong << " of " << inside << " inside and " << free << " free voxels with the wrong sign";
}

MapConfig mapConfig(float voxel_m) {
  MapConfig config;
  config.voxel_size_m = voxel_m;
  return config;
}

/// updateAll on `dataset` fused at `voxel_m`, held to the reference and the brute force.
template <typename Sdf>
void checkFullUpdate(const Dataset& dataset, std::size_t frames, float voxel_m, Sdf&& true_sdf) {
  DeviceFusion fusion(test::sharedContext(), mapConfig(voxel_m));
  const TsdfMap tsdf = test::fuseOnDevice(dataset, mapConfig(voxel_m), frames, 1, &fusion);
  DeviceEsdf esdf(test::sharedContext(), fusion.map());
  const EsdfUpdateStats stats = esdf.updateAll();
  EsdfMap device;
  esdf.download(device);
  char voxel_text[32];
  std::snprintf(voxel_text, sizeof(voxel_text), " at %.2f m", voxel_m);
  const std::string what = dataset.name() + voxel_text;
  std::printf("[ esdf ] %s: full update %.1f ms device, %u blocks\n", what.c_str(), stats.device_ms,
              stats.blocks_updated);
  expectWithinTolerance(compareEsdf(device, computeEsdfReference(tsdf, esdf.config())),
                        what + " vs reference");
  expectWithinTolerance(compareBruteForce(device, tsdf, voxel_m < 0.07f ? 37 : 11),
                        what + " vs brute force");
  expectSigns(device, fusion.config().truncationDistance(), true_sdf);
}

std::shared_ptr<const sim::World> roomWorld() {
  return std::make_shared<const sim::World>(sim::World::load(sim::findWorld("room")));
}

sim::SimSessionConfig sessionConfig(int frames) {
  sim::SimSessionConfig config;
  config.max_frames = frames;  // noise on (the camera's default)
  return config;
}

TEST(Esdf, DeviceIsExactOnAnalyticScene) {
  sim::AnalyticDatasetConfig config;
  config.frame_count = 6;
  const sim::AnalyticDataset dataset(config);
  for (const float voxel_m : {0.05f, 0.10f}) {
    checkFullUpdate(dataset, 6, voxel_m,
                    [&](const Eigen::Vector3f& p) { return dataset.scene().signedDistance(p); });
  }
}

TEST(Esdf, DeviceIsExactOnSimulatedRoom) {
  const sim::SimSessionDataset session(roomWorld(), 0, sessionConfig(10));
  for (const float voxel_m : {0.05f, 0.10f}) {
    checkFullUpdate(session, 10, voxel_m,
                    [&](const Eigen::Vector3f& p) { return session.scene().signedDistance(p); });
  }
}

/// Fuses frames [begin, end) of `dataset`, updating the ESDF incrementally after each one.
double fuseIncrementally(const Dataset& dataset, std::size_t begin, std::size_t end,
                         DeviceFusion& fusion, DeviceEsdf& esdf) {
  double device_ms = 0.0;
  for (std::size_t i = begin; i < end && i < dataset.size(); ++i) {
    const FrameStats stats = fusion.integrate(dataset.load(i), dataset.intrinsics());
    EXPECT_EQ(fusion.lastTouchedBlocks().size(), stats.touched_blocks);
    esdf.markDirty(fusion.lastTouchedBlocks());
    device_ms += esdf.updateIncremental().device_ms;
  }
  return device_ms / static_cast<double>(end - begin);
}

/// The incrementally kept ESDF against a fresh updateAll of the same map (and the reference).
void expectEqualsBatch(DeviceEsdf& incremental, const std::string& what) {
  EsdfMap kept, fresh;
  incremental.download(kept);
  DeviceEsdf batch(test::sharedContext(), incremental.tsdf(), incremental.config());
  batch.updateAll();
  batch.download(fresh);
  expectWithinTolerance(compareEsdf(kept, fresh), what + ": incremental vs updateAll");
  TsdfMap tsdf(incremental.tsdf().config());
  incremental.tsdf().download(tsdf);
  expectWithinTolerance(compareEsdf(kept, computeEsdfReference(tsdf, incremental.config())),
                        what + ": incremental vs reference");
}

TEST(Esdf, IncrementalEqualsBatchOverASession) {
  const sim::SimSessionDataset session(roomWorld(), 1, sessionConfig(8));
  DeviceFusion fusion(test::sharedContext(), mapConfig(0.05f));
  fusion.setTrackTouchedBlocks(true);
  DeviceEsdf esdf(test::sharedContext(), fusion.map());
  const double per_frame_ms = fuseIncrementally(session, 0, session.size(), fusion, esdf);
  const double full_ms = DeviceEsdf(test::sharedContext(), fusion.map()).updateAll().device_ms;
  std::printf("[ esdf ] room session at 0.05 m: incremental %.1f ms/frame, full %.1f ms device\n",
              per_frame_ms, full_ms);
  expectEqualsBatch(esdf, "room session");
}

TEST(Esdf, ObjectThatAppearsAndDisappearsLeavesNoStaleObstacle) {
  sim::Box box;  // a free spot on the floor of the default scene, seen from the whole arc
  box.centre_W = Eigen::Vector3d(-1.0, -0.3, 0.15);
  box.half_extents_m = Eigen::Vector3d(0.2, 0.2, 0.15);
  sim::AnalyticScene with_box = sim::makeDefaultScene();
  with_box.add(box);
  const auto poses = sim::makeDefaultTrajectory(12);
  sim::AnalyticDatasetConfig data_config;
  data_config.render_color = false;
  const sim::AnalyticDataset before(with_box, poses, data_config);
  const sim::AnalyticDataset after(sim::makeDefaultScene(), poses, data_config);

  MapConfig map = mapConfig(0.05f);
  map.truncation_voxels = 8.0f;  // the floor's band covers where the box was (0.3 m high)
  map.weight_mode = WeightMode::kConstant;
  map.max_weight = 3.0f;  // recent frames dominate, as a map of a changing scene would want
  DeviceFusion fusion(test::sharedContext(), map);
  fusion.setTrackTouchedBlocks(true);
  DeviceEsdf esdf(test::sharedContext(), fusion.map());
  const GlobalVoxelIndex top(static_cast<int>(std::floor(-1.0 / 0.05)),
                             static_cast<int>(std::floor(-0.3 / 0.05)), 5);  // z = 0.25..0.3 m
  fuseIncrementally(before, 0, 12, fusion, esdf);
  expectEqualsBatch(esdf, "with the box");
  EsdfMap with;
  esdf.download(with);
  ASSERT_NE(with.findVoxel(top), nullptr);
  EXPECT_LE(std::fabs(with.findVoxel(top)->distance_m), 0.05f) << "the box top is an obstacle";

  fuseIncrementally(after, 0, 12, fusion, esdf);
  expectEqualsBatch(esdf, "after the box left");
  EsdfMap without;
  esdf.download(without);
  EXPECT_GT(without.findVoxel(top)->distance_m, 0.15f) << "stale obstacle where the box was";
  expectSigns(without, map.truncationDistance(),
              [&](const Eigen::Vector3f& p) { return after.scene().signedDistance(p); });
}

TEST(Esdf, EmptyMapIsDefined) {
  DeviceFusion fusion(test::sharedContext(), mapConfig(0.05f));
  DeviceEsdf esdf(test::sharedContext(), fusion.map());
  EXPECT_EQ(esdf.updateAll().blocks_updated, 0u);
  esdf.markDirty({BlockIndex(1, 2, 3)});
  EXPECT_EQ(esdf.updateIncremental().blocks_updated, 0u);
  EsdfMap out;
  esdf.download(out);
  EXPECT_TRUE(out.blocks.empty());
  TsdfMap empty(mapConfig(0.05f));
  EXPECT_TRUE(computeEsdfReference(empty, EsdfConfig{}).blocks.empty());
}

TEST(Esdf, SlabsAndDeviceAddressesStayExact) {
  sim::AnalyticDatasetConfig config;
  config.frame_count = 3;
  const sim::AnalyticDataset dataset(config);
  DeviceFusion fusion(test::sharedContext(), mapConfig(0.10f));
  const TsdfMap tsdf = test::fuseOnDevice(dataset, mapConfig(0.10f), 3, 1, &fusion);
  EsdfConfig esdf_config;
  esdf_config.max_distance_m = 0.8f;
  DeviceEsdf esdf(test::sharedContext(), fusion.map(), esdf_config);
  esdf.setWorkingMemoryBudget(256u << 10, 16u << 10);  // forces slabs and chunked lines
  EXPECT_GT(esdf.updateAll().slabs, 1u);
  EsdfMap device;
  esdf.download(device);
  const EsdfMap reference = computeEsdfReference(tsdf, esdf_config);
  expectWithinTolerance(compareEsdf(device, reference), "slabs");
  esdf.setBindingLimit(0);  // every buffer by device address
  esdf.updateAll();
  esdf.download(device);
  expectWithinTolerance(compareEsdf(device, reference), "device addresses");
  esdf.setWorkingMemoryBudget(4u << 10, 64u << 10);
  EXPECT_THROW(esdf.updateAll(), DeviceError);
}

}  // namespace
}  // namespace strata

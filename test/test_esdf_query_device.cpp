// Device ESDF queries (EsdfQueryKernel) against the host queries (EsdfQuery): the analytic sphere
// ESDF uploaded by hand, and the built-in analytic scene fused and transformed by DeviceEsdf.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "esdf_query_compare.h"
#include "esdf_sphere_scene.h"
#include "fusion_fixture.h"
#include "strata/esdf/esdf.h"
#include "strata/esdf/esdf_query_kernel.h"
#include "strata/sim/analytic_dataset.h"

namespace strata {
namespace {

using test::SphereEsdfScene;

TEST(EsdfQueryKernel, EqualsHostQueriesOnTheAnalyticSphere) {
  const SphereEsdfScene& scene = test::sphereEsdfScene();
  const test::DeviceSphereEsdf device = test::uploadSphereEsdf(test::sharedContext(), scene);
  EsdfConfig config;
  config.max_distance_m = SphereEsdfScene::kMaxDistanceM;
  const DeviceEsdfView view{*device.tsdf, device.esdf_pool, device.tsdf->blockCount(), config};
  std::vector<Eigen::Vector3f> points =
      test::awayFromVoxelFaces(test::randomPointsIn(Eigen::Vector3f::Constant(-1.3f),
                                                    Eigen::Vector3f::Constant(1.3f), 20000, 11),
                               SphereEsdfScene::kVoxelSizeM);
  test::appendBadPoints(points);
  EsdfQueryKernel kernel(test::sharedContext());
  const EsdfQuery host(scene.map);
  for (const bool by_address : {false, true}) {  // the pool through its binding, then by address
    kernel.setForcePoolByAddress(by_address);
    for (const UnknownPolicy policy : {UnknownPolicy::kOccupied, UnknownPolicy::kFree}) {
      const EsdfSphereTest spheres{0.1f, 0.05f, policy};
      const EsdfQueryResult result = kernel.run(view, points, spheres);
      test::expectDeviceEqualsHost(host, points, spheres, result);
    }
  }
  // Without a sphere test: samples only.
  const EsdfQueryResult samples_only = kernel.run(view, points);
  EXPECT_TRUE(samples_only.sphere_free.empty());
  ASSERT_EQ(samples_only.samples.size(), points.size());
  EXPECT_TRUE(kernel.run(view, {}).samples.empty());
}

TEST(EsdfQueryKernel, BadRadiiAreNeverFree) {
  const SphereEsdfScene& scene = test::sphereEsdfScene();
  const test::DeviceSphereEsdf device = test::uploadSphereEsdf(test::sharedContext(), scene);
  EsdfConfig config;
  config.max_distance_m = SphereEsdfScene::kMaxDistanceM;
  const DeviceEsdfView view{*device.tsdf, device.esdf_pool, device.tsdf->blockCount(), config};
  EsdfQueryKernel kernel(test::sharedContext());
  const std::vector<Eigen::Vector3f> points{{-0.9f, 0.0f, 0.0f}, {1.0f, 1.0f, 1.0f}};
  for (const float radius : {std::numeric_limits<float>::quiet_NaN(), -0.1f, 1.5f}) {
    const EsdfQueryResult r =
        kernel.run(view, points, EsdfSphereTest{radius, 0.0f, UnknownPolicy::kFree});
    EXPECT_EQ(r.sphere_free, (std::vector<std::uint8_t>{0, 0})) << radius;
  }
  const EsdfQueryResult ok =
      kernel.run(view, points, EsdfSphereTest{0.1f, 0.0f, UnknownPolicy::kFree});
  EXPECT_EQ(ok.sphere_free, (std::vector<std::uint8_t>{1, 1}));
}

/// The bounding box of the map's blocks, metres.
void blockBounds(const EsdfMap& map, Eigen::Vector3f* lo, Eigen::Vector3f* hi) {
  Eigen::Vector3i lo_b = Eigen::Vector3i::Constant(1 << 30), hi_b = -lo_b;
  for (const auto& [b, block] : map.blocks) {
    lo_b = lo_b.cwiseMin(b);
    hi_b = hi_b.cwiseMax(b);
  }
  const float block_m = map.voxel_size_m * kBlockEdge;
  *lo = lo_b.cast<float>() * block_m;
  *hi = (hi_b + Eigen::Vector3i::Ones()).cast<float>() * block_m;
}

TEST(EsdfQueryKernel, EqualsHostQueriesOnAFusedScene) {
  sim::AnalyticDatasetConfig dataset_config;
  dataset_config.frame_count = 12;
  dataset_config.render_color = false;
  const sim::AnalyticDataset dataset(dataset_config);
  MapConfig config;
  config.voxel_size_m = 0.05f;
  DeviceFusion fusion(test::sharedContext(), config);
  test::fuseOnDevice(dataset, config, dataset.size(), 1, &fusion);
  DeviceEsdf esdf(test::sharedContext(), fusion.map());
  esdf.updateAll();
  EsdfMap host_map;
  esdf.download(host_map);
  ASSERT_GT(host_map.blocks.size(), 100u);
  Eigen::Vector3f lo, hi;
  blockBounds(host_map, &lo, &hi);
  // A little beyond the blocks on every side, so outside points are asked too.
  const Eigen::Vector3f pad = Eigen::Vector3f::Constant(0.3f);
  std::vector<Eigen::Vector3f> points = test::randomPointsIn(lo - pad, hi + pad, 10000, 12);
  // As many near observed voxels: most of the box is outside the band of allocated blocks.
  const std::vector<Eigen::Vector3f> jitter = test::randomPointsIn(
      Eigen::Vector3f::Constant(-0.1f), Eigen::Vector3f::Constant(0.1f), 10000, 13);
  std::size_t j = 0;
  for (const auto& [b, block] : host_map.blocks) {
    for (int i = 0; i < kVoxelsPerBlock && j < jitter.size(); i += 37) {
      if (!esdfObserved(block[i])) continue;
      const GlobalVoxelIndex v = b * kBlockEdge + Eigen::Vector3i(i % 8, (i / 8) % 8, i / 64);
      points.push_back(voxelCenter(v, config.voxel_size_m) + jitter[j++]);
    }
  }
  points = test::awayFromVoxelFaces(points, config.voxel_size_m);
  test::appendBadPoints(points);
  EsdfQueryKernel kernel(test::sharedContext());
  const EsdfQuery host(host_map);
  for (const UnknownPolicy policy : {UnknownPolicy::kOccupied, UnknownPolicy::kFree}) {
    const EsdfSphereTest spheres{0.1f, 0.05f, policy};
    test::expectDeviceEqualsHost(host, points, spheres, kernel.run(esdf, points, spheres));
  }
}

}  // namespace
}  // namespace strata

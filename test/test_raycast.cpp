// Raycast: device against the C++ reference, against exact depth on the analytic scene, and
// against the measured depth of the real sample.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "strata/core/error.h"
#include "fusion_fixture.h"
#include "strata/io/open_dataset.h"
#include "strata/raycast/raycast.h"
#include "strata/sim/analytic_dataset.h"
#include "test_utils.h"

namespace strata {
namespace {

CameraIntrinsics halfResolution(const CameraIntrinsics& in) {
  CameraIntrinsics out = in;
  out.width_px /= 2;
  out.height_px /= 2;
  out.fx_px /= 2;
  out.fy_px /= 2;
  out.cx_px = (in.cx_px + 0.5f) / 2 - 0.5f;
  out.cy_px = (in.cy_px + 0.5f) / 2 - 0.5f;
  return out;
}

TEST(Raycast, DeviceMatchesReferenceAndExactDepth) {
  sim::AnalyticDatasetConfig dataset_config;
  dataset_config.frame_count = 24;
  const sim::AnalyticDataset dataset(dataset_config);
  MapConfig config;
  DeviceFusion fusion(test::sharedContext(), config);
  const TsdfMap map = test::fuseOnDevice(dataset, config, 24, 2, &fusion);

  // Render from a pose between two input poses, at half resolution to keep the reference quick.
  const CameraIntrinsics intrinsics = halfResolution(dataset.intrinsics());
  const Eigen::Isometry3d T_W_C = dataset.poses()[5];
  RaycastKernel kernel(test::sharedContext());
  const RaycastImage device = kernel.run(fusion.map(), intrinsics, T_W_C);
  const RaycastImage reference = raycastReference(map, intrinsics, T_W_C);
  const DepthImage exact = dataset.scene().renderDepth(intrinsics, T_W_C, 10.0f);

  std::size_t both = 0, agree = 0, hit_mismatch = 0, near_exact = 0, exact_valid = 0;
  std::size_t with_normal = 0;
  for (std::size_t i = 0; i < device.hit.size(); ++i) {
    if (device.hit[i] != reference.hit[i]) ++hit_mismatch;
    if (device.hit[i] && reference.hit[i]) {
      ++both;
      if (std::abs(device.depth.depth_m[i] - reference.depth.depth_m[i]) <= 0.001f) ++agree;
    }
    if (device.hit[i] && exact.depth_m[i] > 0.0f) {
      ++exact_valid;
      if (std::abs(device.depth.depth_m[i] - exact.depth_m[i]) <= 0.5f * config.voxel_size_m) {
        ++near_exact;
      }
      with_normal += device.normal_W[i].norm() > 0.99f ? 1 : 0;
    }
  }
  ASSERT_GT(both, device.hit.size() / 2) << "most pixels should see the scene";
  EXPECT_LE(hit_mismatch, device.hit.size() / 1000);
  EXPECT_GE(double(agree) / double(both), 0.999);
  // Silhouettes and grazing floor far away hold the pixels that miss by more than half a voxel.
  EXPECT_GE(double(near_exact) / double(exact_valid), 0.95);
  // Normals need observed neighbours one voxel around the hit; the band's edges lack them.
  EXPECT_GE(double(with_normal) / double(exact_valid), 0.97);
}

TEST(Raycast, RenderingReproducesMeasuredDepthOnRedkitchen) {
  STRATA_REQUIRE_DATA("redkitchen", path);
  const auto dataset = openDataset(path);
  MapConfig config;
  DeviceFusion fusion(test::sharedContext(), config);
  for (std::size_t i = 0; i < dataset->size(); ++i) {
    fusion.integrate(dataset->load(i), dataset->intrinsics());
  }
  RaycastKernel kernel(test::sharedContext());
  for (std::size_t i = 0; i < dataset->size(); i += 10) {
    const RgbdFrame frame = dataset->load(i);
    const RaycastImage rendered = kernel.run(fusion.map(), dataset->intrinsics(), frame.T_W_C);
    std::vector<float> differences;
    for (std::size_t p = 0; p < rendered.hit.size(); ++p) {
      const float measured = frame.depth.depth_m[p];
      if (rendered.hit[p] && measured >= config.min_depth_m && measured <= config.max_depth_m) {
        differences.push_back(std::abs(rendered.depth.depth_m[p] - measured));
      }
    }
    ASSERT_GT(differences.size(), rendered.hit.size() / 4) << "frame " << i;
    std::nth_element(differences.begin(), differences.begin() + differences.size() / 2,
                     differences.end());
    EXPECT_LE(differences[differences.size() / 2], 0.015f) << "frame " << i;
  }
}

TEST(Raycast, EmptyMapRendersNothing) {
  MapConfig config;
  DeviceFusion fusion(test::sharedContext(), config);
  RaycastKernel kernel(test::sharedContext());
  const CameraIntrinsics intrinsics;
  const RaycastImage image = kernel.run(fusion.map(), intrinsics, Eigen::Isometry3d::Identity());
  EXPECT_EQ(std::count(image.hit.begin(), image.hit.end(), 1), 0);
  Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
  bad.matrix()(1, 1) = std::nan("");
  EXPECT_THROW(kernel.run(fusion.map(), intrinsics, bad), InputError);
}

}  // namespace
}  // namespace strata

// Free space from skipped keyframes' vacated samples (change/carry_free.h): the update agrees with
// fusing the keyframe where it applies and with the true geometry, counts once per view, leaves
// carried-forward values out where the session has its own evidence, survives bad input, and lets
// the reference detector segment an object's earlier instance from three unfused views of its
// vacated place (and not from two).
#include <gtest/gtest.h>

#include <cmath>

#include "change/carry_forward.h"
#include "change/change_detector.h"
#include "change/objects.h"
#include "change_test_scene.h"
#include "core/error.h"
#include "kernels/tsdf_integration.h"

namespace strata::change {
namespace {

using test::kBoxA;
using test::kVoxel;

CameraIntrinsics smallCamera() {
  CameraIntrinsics k;
  k.width_px = 64;
  k.height_px = 48;
  k.fx_px = k.fy_px = 40.0f;
  k.cx_px = 31.5f;
  k.cy_px = 23.5f;
  return k;
}

MapConfig fusionConfig() {
  MapConfig c;
  c.voxel_size_m = kVoxel;
  c.weight_mode = WeightMode::kConstant;
  c.allocate_free_space = true;
  return c;
}

constexpr float kCellPx = 4.0f;

/// Grid samples (every kCellPx, offset half a cell) inside pixel box [u0, u1) x [v0, v1).
std::vector<VacatedSample> gridSamples(int u0, int u1, int v0, int v1, float surface_m,
                                       float measured_m) {
  std::vector<VacatedSample> out;
  for (int v = 2; v < 48; v += 4) {
    for (int u = 2; u < 64; u += 4) {
      if (u < u0 || u >= u1 || v < v0 || v >= v1) continue;
      out.push_back({static_cast<float>(u), static_cast<float>(v), surface_m, measured_m});
    }
  }
  return out;
}

FreeSpaceConfig cellConfig() {
  FreeSpaceConfig c;
  c.cell_px = kCellPx;
  return c;
}

TEST(FreeSpace, AgreesWithFusingTheKeyframeWhereItUpdates) {
  // A box's front face stood 1.5 m in front of the camera; now the camera sees a wall at 3 m.
  const CameraIntrinsics k = smallCamera();
  const Eigen::Isometry3d T_W_C = Eigen::Isometry3d(Eigen::Translation3d(0.1, -0.2, 0.3));
  VacatedView view;
  view.T_W_C = T_W_C.cast<float>();
  view.samples = gridSamples(20, 40, 16, 32, 1.5f, 3.0f);
  ASSERT_EQ(view.samples.size(), 20u);
  TsdfMap free(fusionConfig());
  VoxelSet updated;
  const FreeSpaceStats stats = integrateFreeSpace({view}, k, cellConfig(), free, &updated);
  EXPECT_EQ(stats.views, 1u);
  EXPECT_EQ(stats.samples, 20u);
  EXPECT_EQ(stats.voxels, updated.size());
  // The band is 2 x 0.13 m deep; the cells cover 20 x 16 px = 0.75 x 0.6 m at 1.5 m.
  EXPECT_GT(updated.size(), 4000u);

  RgbdFrame frame;
  frame.T_W_C = T_W_C;
  frame.depth = DepthImage(k.width_px, k.height_px, 3.0f);
  TsdfMap fused(fusionConfig());
  integrateFrameReference(fused, frame, k, 1);
  const float truncation_m = fusionConfig().truncationDistance();
  const Eigen::Isometry3f T_C_W = view.T_W_C.inverse();
  for (const GlobalVoxelIndex& v : updated) {
    const TsdfVoxel* f = free.findVoxel(v);
    const TsdfVoxel* g = fused.findVoxel(v);
    ASSERT_NE(f, nullptr);
    ASSERT_NE(g, nullptr) << "fusing the keyframe touches every voxel the samples update";
    EXPECT_FLOAT_EQ(f->tsdf_m, g->tsdf_m);
    EXPECT_FLOAT_EQ(f->weight, g->weight);
    // Ground truth: free space within the band around the old face, in front of the wall.
    const Eigen::Vector3f centre_C = T_C_W * voxelCenter(v, kVoxel);
    EXPECT_NEAR(centre_C.z(), 1.5f, 0.13f + 1e-4f);
    EXPECT_GE(3.0f - centre_C.z(), truncation_m);
  }
}

TEST(FreeSpace, CountsOneObservationPerViewAndStopsShortOfTheMeasuredSurface) {
  const CameraIntrinsics k = smallCamera();
  VacatedView view;
  // The measured wall lies 0.15 m behind the old face: the band ends truncation (8 cm) before it.
  view.samples = gridSamples(28, 36, 20, 28, 1.0f, 1.15f);
  TsdfMap map(fusionConfig());
  const GlobalVoxelIndex centre(0, 0, 48);  // on the optical axis at z = 0.97 m
  map.allocateVoxel(centre) = TsdfVoxel{-0.02f, 1.0f, 9u};
  VoxelSet updated;
  // Two overlapping copies of the samples in one view still count once per voxel.
  VacatedView doubled = view;
  doubled.samples.insert(doubled.samples.end(), view.samples.begin(), view.samples.end());
  integrateFreeSpace({doubled, view}, k, cellConfig(), map, &updated);
  const TsdfVoxel* voxel = map.findVoxel(centre);
  ASSERT_NE(voxel, nullptr);
  EXPECT_FLOAT_EQ(voxel->weight, 3.0f);
  EXPECT_NEAR(voxel->tsdf_m, (-0.02f + 2 * 0.08f) / 3.0f, 1e-6f);
  EXPECT_EQ(voxel->color_rgba, 9u) << "free space carries no colour";
  for (const GlobalVoxelIndex& v : updated) {
    EXPECT_LE((v.z() + 0.5f) * kVoxel, 1.15f - 0.08f + 1e-5f);
    EXPECT_GE((v.z() + 0.5f) * kVoxel, 1.0f - 0.13f - 1e-5f);
  }
}

TEST(FreeSpace, BadInputIsSkippedOrNamed) {
  const CameraIntrinsics k = smallCamera();
  TsdfMap map(fusionConfig());
  VacatedView bad_samples;
  bad_samples.samples = {{NAN, 10.0f, 1.0f, 2.0f},
                         {10.0f, 10.0f, NAN, 2.0f},
                         {10.0f, 10.0f, 1.0f, NAN},
                         {10.0f, 10.0f, 2.0f, 1.0f},   // measured in front: nothing free
                         {10.0f, 10.0f, 1.0f, 9.0f}};  // beyond the fusion's range
  const FreeSpaceStats stats = integrateFreeSpace({bad_samples}, k, cellConfig(), map);
  EXPECT_EQ(stats.samples, 5u);
  EXPECT_EQ(stats.voxels, 0u);
  EXPECT_EQ(map.blockCount(), 0u);
  VacatedView bad_pose = bad_samples;
  bad_pose.T_W_C.translation().x() = NAN;
  EXPECT_THROW(integrateFreeSpace({bad_pose}, k, cellConfig(), map), InputError);
  FreeSpaceConfig bad_config;
  bad_config.band_m = 0.0f;
  EXPECT_THROW(integrateFreeSpace({}, k, bad_config, map), InputError);
  bad_config = FreeSpaceConfig{};
  bad_config.cell_px = NAN;
  EXPECT_THROW(integrateFreeSpace({}, k, bad_config, map), InputError);
}

TEST(FreeSpace, CarryingForwardLeavesTheSessionsOwnEvidenceAlone) {
  MapConfig c;
  c.voxel_size_m = kVoxel;
  TsdfMap latest(c), session(c);
  for (int x = 0; x < 3; ++x) latest.allocateVoxel({x, 0, 0}) = TsdfVoxel{-0.01f, 10.0f, 0u};
  session.allocateVoxel({1, 0, 0}) = TsdfVoxel{0.08f, 1.0f, 0u};  // one free observation
  const VoxelSet own{GlobalVoxelIndex(1, 0, 0)};
  const ConfirmedPoint point{Eigen::Vector3f(1.5f, 0.5f, 0.5f) * kVoxel, 1.6f * kVoxel};
  const CarryStats stats = carryObserved(latest, {point}, 3.0f, session, &own);
  EXPECT_EQ(stats.voxels, 2u);
  EXPECT_FLOAT_EQ(session.findVoxel({1, 0, 0})->tsdf_m, 0.08f);
  EXPECT_FLOAT_EQ(session.findVoxel({0, 0, 0})->tsdf_m, -0.01f);
}

/// Looking straight down from `eye_W` (camera z = world -z).
Eigen::Isometry3f lookingDown(const Eigen::Vector3f& eye_W) {
  Eigen::Matrix3f R;
  R.col(0) = Eigen::Vector3f::UnitX();
  R.col(1) = -Eigen::Vector3f::UnitY();
  R.col(2) = -Eigen::Vector3f::UnitZ();
  Eigen::Isometry3f T = Eigen::Isometry3f::Identity();
  T.linear() = R;
  T.translation() = eye_W;
  return T;
}

/// The samples of a camera looking down whose rays met box A before the floor (z = 0): the box's
/// surface and the floor's depth, from exact ray intersections.
VacatedView boxVacatedView(const Eigen::Vector3f& eye_W, const CameraIntrinsics& k) {
  VacatedView view;
  view.T_W_C = lookingDown(eye_W);
  const Eigen::AlignedBox3f box = kBoxA.cast<float>();
  for (int v = 2; v < k.height_px; v += 4) {
    for (int u = 2; u < k.width_px; u += 4) {
      const Eigen::Vector3f ray_C((u - k.cx_px) / k.fx_px, (v - k.cy_px) / k.fy_px, 1.0f);
      const Eigen::Vector3f dir_W = view.T_W_C.linear() * ray_C;  // advances 1 in camera z
      float t_in = 0.0f, t_out = INFINITY;                        // slab intersection, t = camera z
      for (int a = 0; a < 3; ++a) {
        const float t0 = (box.min()[a] - eye_W[a]) / dir_W[a];
        const float t1 = (box.max()[a] - eye_W[a]) / dir_W[a];
        t_in = std::max(t_in, std::min(t0, t1));
        t_out = std::min(t_out, std::max(t0, t1));
      }
      const float floor_t = eye_W.z() / -dir_W.z();
      if (t_in < t_out && t_in < floor_t) {
        view.samples.push_back({static_cast<float>(u), static_cast<float>(v), t_in, floor_t});
      }
    }
  }
  return view;
}

TEST(FreeSpace, ThreeUnfusedViewsOfAVacatedPlaceLetTheDetectorFindTheEarlierInstance) {
  // Session 0: box A on the floor, everything observed. Session 1: the box is gone, and the
  // session's own layer is unobserved within 0.3 m of it (it fused no frame of that place).
  const auto everywhere = [](const Eigen::Vector3d&) { return true; };
  const auto away_from_box = [](const Eigen::Vector3d& p) {
    return kBoxA.exteriorDistance(p) > 0.3;
  };
  const auto floor_map = [](bool with_box, const test::PointTest& observed) {
    return test::makeSdfMap(
        [&](const Eigen::Vector3d& p) {
          return with_box ? std::min(p.z(), test::boxSdf(p, kBoxA)) : p.z();
        },
        {0, 0, -0.1}, {2, 2, 1.1}, kVoxel, observed);
  };
  const CameraIntrinsics k = smallCamera();
  const std::vector<VacatedView> views{boxVacatedView({0.7f, 0.65f, 1.6f}, k),
                                       boxVacatedView({0.6f, 0.7f, 1.5f}, k),
                                       boxVacatedView({0.8f, 0.6f, 1.7f}, k)};
  ChangeConfig config;
  config.min_weight = 3.0f;  // the demo's: three frames with constant weights
  for (const std::size_t view_count : {0u, 2u, 3u}) {
    ChangeDetector detector(floor_map(true, everywhere).config(), config);
    detector.endSession(detector.addSessionMap(floor_map(true, everywhere)));
    const int second = detector.addSessionMap(floor_map(false, away_from_box));
    TsdfMap layer = detector.sessionMap(second);
    const std::vector<VacatedView> used(views.begin(), views.begin() + view_count);
    const FreeSpaceStats stats = integrateFreeSpace(used, k, cellConfig(), layer);
    EXPECT_EQ(stats.voxels > 0, view_count > 0);
    detector.replaceSessionMap(second, layer);
    detector.endSession(second);
    const auto objects = sessionObjects(detector, 0);
    if (view_count < 3) {
      EXPECT_TRUE(objects.empty()) << view_count << " views leave the place below min_weight";
      continue;
    }
    ASSERT_EQ(objects.size(), 1u);
    // The box as the earlier session held it: its footprint, up to its top.
    for (int a = 0; a < 2; ++a) {
      EXPECT_NEAR(objects[0].bbox.min()[a], kBoxA.min()[a], 2 * kVoxel) << "axis " << a;
      EXPECT_NEAR(objects[0].bbox.max()[a], kBoxA.max()[a], 2 * kVoxel) << "axis " << a;
    }
    EXPECT_NEAR(objects[0].bbox.max().z(), kBoxA.max().z(), 2 * kVoxel);
  }
}

}  // namespace
}  // namespace strata::change

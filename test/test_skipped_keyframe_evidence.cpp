// Free space from skipped keyframes' vacated samples (change/skipped_keyframe_evidence.h): the update agrees with
// fusing the keyframe where it applies and with the true geometry, counts once per view, leaves
// carried-forward values out where the session has its own evidence, survives bad input, and lets
// the reference detector segment an object's earlier instance from three unfused views of its
// vacated place (and not from two).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "strata/change/carry_forward.h"
#include "strata/change/change_detector.h"
#include "strata/change/object_discovery.h"
#include "change_test_scene.h"
#include "strata/core/error.h"
#include "strata/integrate/tsdf_integration.h"

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

constexpr int kCellPx = 4;

/// Grid samples (every kCellPx, offset half a cell) inside pixel box [u0, u1) x [v0, v1).
std::vector<VacatedSample> gridSamples(int u0, int u1, int v0, int v1, float surface_m) {
  std::vector<VacatedSample> out;
  for (int v = 2; v < 48; v += kCellPx) {
    for (int u = 2; u < 64; u += kCellPx) {
      if (u < u0 || u >= u1 || v < v0 || v >= v1) continue;
      out.push_back({u, v, surface_m});
    }
  }
  return out;
}

FreeSpaceConfig placeConfig(float radius_m = 0.3f) {
  FreeSpaceConfig c;
  c.cell_px = kCellPx;
  c.place_radius_m = radius_m;
  return c;
}

/// A view of `samples` whose keyframe measured `depth`, kept around them as the selection does.
ChangedView viewOf(const Eigen::Isometry3f& T_W_C, std::vector<VacatedSample> samples,
                   const DepthImage& depth, const FreeSpaceConfig& config = placeConfig()) {
  ChangedView view{T_W_C, std::move(samples), DepthTiles(config.cell_px)};
  keepDepthAround(depth, smallCamera(), config, view);
  return view;
}

/// Camera z and nearest pixel of a world point.
struct Projected {
  float z_m;
  int u_px, v_px;
};
Projected project(const Eigen::Isometry3f& T_C_W, const Eigen::Vector3f& p_W) {
  const CameraIntrinsics k = smallCamera();
  const Eigen::Vector3f c = T_C_W * p_W;
  return {c.z(), static_cast<int>(std::floor(k.fx_px * c.x() / c.z() + k.cx_px + 0.5f)),
          static_cast<int>(std::floor(k.fy_px * c.y() / c.z() + k.cy_px + 0.5f))};
}

TEST(FreeSpace, DepthTilesKeepTheCellsAroundTheSamplesOnly) {
  DepthImage depth(10, 7);
  for (int v = 0; v < 7; ++v) {
    for (int u = 0; u < 10; ++u) depth.at(u, v) = 1.0f + 0.1f * u + 0.01f * v;
  }
  DepthTiles tiles(4);
  tiles.keep(depth, 7, 9, 5, 6);   // pixels u 7..8, v 5: tiles (1, 1) and (2, 1)
  tiles.keep(depth, 8, 12, 4, 6);  // tile (2, 1) again: kept once
  EXPECT_EQ(tiles.tileCount(), 2u);
  EXPECT_EQ(tiles.pixelCount(), 32u);
  for (int v = 0; v < 7; ++v) {
    for (int u = 0; u < 10; ++u) {
      if (u >= 4 && v >= 4) {
        EXPECT_FLOAT_EQ(tiles.at(u, v), depth.at(u, v)) << u << ", " << v;
      } else {
        EXPECT_TRUE(std::isnan(tiles.at(u, v))) << u << ", " << v;
      }
    }
  }
  EXPECT_TRUE(std::isnan(tiles.at(10, 5))) << "the tile reaches past the image";
  EXPECT_TRUE(std::isnan(tiles.at(5, 8)));
  EXPECT_TRUE(std::isnan(tiles.at(-1, 5)));
  tiles.keep(depth, -5, 0, 0, 3);  // empty after clipping
  EXPECT_EQ(tiles.tileCount(), 2u);
  EXPECT_THROW(DepthTiles(0), InputError);
}

TEST(FreeSpace, KeepsTheDepthWhereThePlaceCanProject) {
  const CameraIntrinsics k = smallCamera();
  const DepthImage depth(k.width_px, k.height_px, 3.0f);
  // A sample at 2 m: the 0.3 m place projects within 40 * 0.3 / 1.7 = 7.06 px, so 8 px.
  const ChangedView view = viewOf(Eigen::Isometry3f::Identity(), {{30, 22, 2.0f}}, depth);
  EXPECT_FLOAT_EQ(view.depth.at(22, 14), 3.0f);
  EXPECT_FLOAT_EQ(view.depth.at(38, 30), 3.0f);
  // Tiles of 4 px aligned at 0: pixels 20..39 x 12..31 are kept, no more.
  EXPECT_EQ(view.depth.tileCount(), 5u * 5u);
  EXPECT_TRUE(std::isnan(view.depth.at(19, 22)));
  EXPECT_TRUE(std::isnan(view.depth.at(40, 22)));
  // Nearer, the place covers more of the image.
  const ChangedView near = viewOf(Eigen::Isometry3f::Identity(), {{30, 22, 0.5f}}, depth);
  EXPECT_GT(near.depth.tileCount(), view.depth.tileCount());
}

TEST(FreeSpace, AgreesWithFusingTheKeyframeWhereItUpdates) {
  // A box was last observed 1.4 to 1.7 m in front of the camera. Now the camera sees a wall at
  // 3 m through its place and, right of pixel column 33, a new board at 1.62 m.
  const CameraIntrinsics k = smallCamera();
  const Eigen::Isometry3f T_W_C(Eigen::Translation3f(0.1f, -0.2f, 0.3f));
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-0.1, -0.35, 1.7),
                                Eigen::Vector3d(0.3, -0.05, 2.0));
  const TsdfMap place = test::makeSdfMap(
      [&](const Eigen::Vector3d& p) { return test::boxSdf(p, box); }, {-0.5, -0.8, 1.2},
      {0.7, 0.4, 2.4}, kVoxel, [](const Eigen::Vector3d&) { return true; });
  DepthImage depth(k.width_px, k.height_px, 3.0f);
  for (int v = 0; v < k.height_px; ++v) {
    for (int u = 33; u < k.width_px; ++u) depth.at(u, v) = 1.62f;
  }
  // The box's face spans u 26..37, v 19..28 at 1.4 m.
  const ChangedView view = viewOf(T_W_C, gridSamples(26, 37, 19, 28, 1.4f), depth);
  ASSERT_EQ(view.samples.size(), 6u);
  TsdfMap free(fusionConfig());
  VoxelSet updated;
  const FreeSpaceStats stats =
      integrateChangedPlaces({view}, k, placeConfig(), place, free, &updated);
  EXPECT_EQ(stats.views, 1u);
  EXPECT_EQ(stats.samples, 6u);
  EXPECT_EQ(stats.voxels, updated.size());
  EXPECT_EQ(stats.depth_pixels, view.depth.pixelCount());
  EXPECT_GT(updated.size(), 2000u) << "most of the box's surface band";

  RgbdFrame frame;
  frame.T_W_C = T_W_C.cast<double>();
  frame.depth = depth;
  TsdfMap fused(fusionConfig());
  integrateFrameReference(fused, frame, k, 1);
  const float truncation_m = fusionConfig().truncationDistance();
  const Eigen::Isometry3f T_C_W = T_W_C.inverse();
  int before_the_board = 0, surface = 0;
  for (const GlobalVoxelIndex& v : updated) {
    const TsdfVoxel* f = free.findVoxel(v);
    const TsdfVoxel* g = fused.findVoxel(v);
    ASSERT_NE(f, nullptr);
    ASSERT_NE(g, nullptr) << "fusing the keyframe touches every voxel the view updates";
    EXPECT_FLOAT_EQ(f->tsdf_m, g->tsdf_m);
    EXPECT_FLOAT_EQ(f->weight, g->weight);
    // Ground truth: the box's place; free where the wall or the board lies beyond it, the
    // board's distance (along the ray) just in front of and behind the board.
    const Eigen::Vector3f centre_W = voxelCenter(v, kVoxel);
    EXPECT_LT(test::boxSdf(centre_W.cast<double>(), box), truncation_m);
    const Projected p = project(T_C_W, centre_W);
    const float measured_m = depth.at(p.u_px, p.v_px);
    if (measured_m - p.z_m >= truncation_m) {
      EXPECT_FLOAT_EQ(f->tsdf_m, truncation_m);
      if (p.u_px >= 33) ++before_the_board;
    } else {
      EXPECT_FLOAT_EQ(measured_m, 1.62f) << "only the board is measured near the box";
      EXPECT_GT(measured_m - p.z_m, -truncation_m);
      ++surface;
    }
  }
  EXPECT_GT(before_the_board, 50) << "the board leaves the box's front free";
  EXPECT_GT(surface, 50) << "the box's voxels at the board take the board's distance";
  // Everything of the box's surface band within the place whose pixel shows the wall is updated.
  int missed = 0;
  for (const auto& [b, block] : place.blocks()) {
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const GlobalVoxelIndex v = b * kBlockEdge + Eigen::Vector3i(i % 8, i / 8 % 8, i / 64);
      if (!(block[i].weight > 0.0f) || !(block[i].tsdf_m < truncation_m)) continue;
      const Projected p = project(T_C_W, voxelCenter(v, kVoxel));
      if (p.u_px < 0 || p.v_px < 0 || p.u_px >= k.width_px || p.v_px >= k.height_px) continue;
      const bool near_a_sample =
          (voxelCenter(v, kVoxel) - T_W_C * Eigen::Vector3f(0.1f, 0.0f, 1.4f)).norm() < 0.2f;
      if (near_a_sample && depth.at(p.u_px, p.v_px) - p.z_m >= truncation_m)
        missed += updated.count(v) == 0;
    }
  }
  EXPECT_EQ(missed, 0);

  // A smaller place: fewer voxels, all among the larger place's.
  VoxelSet small;
  TsdfMap free_small(fusionConfig());
  integrateChangedPlaces({view}, k, placeConfig(0.1f), place, free_small, &small);
  EXPECT_GT(small.size(), 0u);
  EXPECT_LT(small.size(), updated.size());
  for (const GlobalVoxelIndex& v : small) EXPECT_EQ(updated.count(v), 1u);
}

TEST(FreeSpace, AnArrivedSurfaceTakesWhatFusingTheKeyframeGivesIt) {
  // Nothing stood 1.2 m in front of the camera when last observed; now a board stands there
  // (x -0.3..0.2, y -0.25..0.15, 1.2..1.35 m) before a wall at 2 m. The samples on the board
  // measure it in front of the map's surface.
  const CameraIntrinsics k = smallCamera();
  const Eigen::AlignedBox3d board(Eigen::Vector3d(-0.3, -0.25, 1.2),
                                  Eigen::Vector3d(0.2, 0.15, 1.35));
  DepthImage depth(k.width_px, k.height_px, 2.0f);
  for (int v = 0; v < k.height_px; ++v) {
    for (int u = 0; u < k.width_px; ++u) {
      const Eigen::Vector3d at_board((u - k.cx_px) / k.fx_px * 1.2, (v - k.cy_px) / k.fy_px * 1.2,
                                     1.2);
      if (board.contains(at_board + Eigen::Vector3d(0, 0, 1e-6))) depth.at(u, v) = 1.2f;
    }
  }
  ChangedView view{Eigen::Isometry3f::Identity(), {}, DepthTiles(kCellPx), {}};
  for (int v = 2; v < k.height_px; v += kCellPx) {
    for (int u = 2; u < k.width_px; u += kCellPx) {
      if (depth.at(u, v) < 1.5f) view.arrived.push_back({u, v, 1.2f});
    }
  }
  ASSERT_GT(view.arrived.size(), 10u);
  keepDepthAround(depth, k, placeConfig(), view);
  RgbdFrame frame;
  frame.T_W_C = Eigen::Isometry3d::Identity();
  frame.depth = depth;
  TsdfMap fused(fusionConfig());
  integrateFrameReference(fused, frame, k, 1);
  const float truncation_m = fusionConfig().truncationDistance();

  // Last observed: nothing (an empty place), then the board itself (it stood there before).
  const TsdfMap stood = test::makeSdfMap(
      [&](const Eigen::Vector3d& p) { return test::boxSdf(p, board); }, {-0.5, -0.5, 1.0},
      {0.4, 0.4, 1.5}, kVoxel, [](const Eigen::Vector3d&) { return true; });
  for (const bool board_stood : {false, true}) {
    const TsdfMap place = board_stood ? stood : TsdfMap(fusionConfig());
    TsdfMap session(fusionConfig());
    VoxelSet updated, own;
    const FreeSpaceStats stats =
        integrateChangedPlaces({view}, k, placeConfig(), place, session, &updated, &own);
    EXPECT_EQ(stats.arrived_samples, view.arrived.size());
    EXPECT_EQ(stats.samples, 0u);
    EXPECT_EQ(stats.voxels, updated.size());
    int on_board = 0, inside = 0;
    for (const GlobalVoxelIndex& v : updated) {
      const TsdfVoxel* f = session.findVoxel(v);
      const TsdfVoxel* g = fused.findVoxel(v);
      if (g == nullptr) {
        // Fusion allocates free space only along a sparse set of rays: this is a free
        // observation of what stood there, and only the board that stood gives those.
        EXPECT_TRUE(board_stood);
        EXPECT_FLOAT_EQ(f->tsdf_m, truncation_m);
        continue;
      }
      EXPECT_FLOAT_EQ(f->tsdf_m, g->tsdf_m);
      EXPECT_FLOAT_EQ(f->weight, g->weight);
      // Ground truth: within the truncation band of the board (nothing else lies in reach).
      const Eigen::Vector3f c = voxelCenter(v, kVoxel);
      const double true_sdf = test::boxSdf(c.cast<double>(), board);
      EXPECT_LT(std::abs(true_sdf), truncation_m + kVoxel) << c.transpose();
      on_board += std::abs(true_sdf) < kVoxel;
      inside += f->tsdf_m < 0.0f;
      // Own evidence where the last observation disagrees: all of the board's inside when
      // nothing stood there, none of its face's interior when the board stood there.
      const bool interior = c.x() > -0.26f && c.x() < 0.16f && c.y() > -0.21f && c.y() < 0.11f;
      if (!board_stood) {
        EXPECT_EQ(own.count(v) > 0, f->tsdf_m < 0.0f) << c.transpose();
      } else if (interior) {
        EXPECT_EQ(own.count(v), 0u) << c.transpose();
      }
    }
    EXPECT_GT(on_board, 200) << "the board's face";
    EXPECT_GT(inside, 200);
    // Every voxel on the board's face that fusing the keyframe observes as a surface, the view
    // observes (free observations there are at the board's edges, where the pixel shows the wall).
    int missed = 0;
    for (const auto& [b, block] : fused.blocks()) {
      for (int i = 0; i < kVoxelsPerBlock; ++i) {
        const GlobalVoxelIndex v = b * kBlockEdge + Eigen::Vector3i(i % 8, i / 8 % 8, i / 64);
        const Eigen::Vector3f c = voxelCenter(v, kVoxel);
        const bool face = std::abs(c.z() - 1.2f) < kVoxel && c.x() > -0.3f && c.x() < 0.2f &&
                          c.y() > -0.25f && c.y() < 0.15f;
        if (face && block[i].weight > 0.0f && block[i].tsdf_m < truncation_m) {
          missed += updated.count(v) == 0;
        }
      }
    }
    EXPECT_EQ(missed, 0);
  }
  // No ring, no arrivals.
  FreeSpaceConfig off = placeConfig();
  off.arrived_ring_cells = 0;
  TsdfMap session(fusionConfig());
  const FreeSpaceStats none =
      integrateChangedPlaces({view}, k, off, TsdfMap(fusionConfig()), session);
  EXPECT_EQ(none.voxels, 0u);
  EXPECT_EQ(none.arrived_samples, 0u) << "arrived samples count only where they are used";
  EXPECT_EQ(session.blockCount(), 0u);
}

TEST(FreeSpace, CountsOneObservationPerViewAndStopsShortOfTheMeasuredSurface) {
  const CameraIntrinsics k = smallCamera();
  // Something was last observed 0.9 to 1.2 m in front of the camera; the wall now measured lies
  // at 1.15 m: what lies truncation (8 cm) before it is free, what lies within truncation of it
  // takes its distance, what lies further behind takes nothing.
  TsdfMap place(fusionConfig());
  for (int z = 45; z < 60; ++z) {
    for (int y = -5; y <= 5; ++y) {
      for (int x = -5; x <= 5; ++x) place.allocateVoxel({x, y, z}) = TsdfVoxel{-0.01f, 5.0f, 0u};
    }
  }
  const DepthImage wall(k.width_px, k.height_px, 1.15f);
  const ChangedView view =
      viewOf(Eigen::Isometry3f::Identity(), gridSamples(28, 36, 20, 28, 1.0f), wall);
  TsdfMap map(fusionConfig());
  const GlobalVoxelIndex centre(0, 0, 48);  // on the optical axis at z = 0.97 m
  map.allocateVoxel(centre) = TsdfVoxel{-0.02f, 1.0f, 9u};
  VoxelSet updated;
  // Two copies of the samples in one view still count once per voxel.
  ChangedView doubled = view;
  doubled.samples.insert(doubled.samples.end(), view.samples.begin(), view.samples.end());
  integrateChangedPlaces({doubled, view}, k, placeConfig(), place, map, &updated);
  const TsdfVoxel* voxel = map.findVoxel(centre);
  ASSERT_NE(voxel, nullptr);
  EXPECT_FLOAT_EQ(voxel->weight, 3.0f);
  EXPECT_NEAR(voxel->tsdf_m, (-0.02f + 2 * 0.08f) / 3.0f, 1e-6f);
  EXPECT_EQ(voxel->color_rgba, 9u) << "free space carries no colour";
  EXPECT_FALSE(updated.empty());
  int free = 0;
  for (const GlobalVoxelIndex& v : updated) {
    const float z_m = (v.z() + 0.5f) * kVoxel;
    EXPECT_LT(z_m, 1.15f + 0.08f);
    const TsdfVoxel* after = map.findVoxel(v);
    if (v == centre) continue;
    if (z_m <= 1.15f - 0.08f + 1e-5f) {
      EXPECT_FLOAT_EQ(after->tsdf_m, 0.08f) << z_m;
      ++free;
    } else {
      EXPECT_LT(after->tsdf_m, 0.08f) << z_m;
    }
    EXPECT_NE(place.findVoxel(v), nullptr) << "only what was last observed";
  }
  EXPECT_GT(free, 0);
}

TEST(FreeSpace, BadInputIsSkippedOrNamed) {
  const CameraIntrinsics k = smallCamera();
  TsdfMap place(fusionConfig());
  for (int z = 40; z < 60; ++z) {
    for (int y = -12; y <= 12; ++y) {
      for (int x = -30; x <= 16; ++x) place.allocateVoxel({x, y, z}) = TsdfVoxel{0.0f, 5.0f, 0u};
    }
  }
  // The depth lies in front of the surface left of column 40, beyond the fusion's range right
  // of it.
  DepthImage depth(k.width_px, k.height_px);
  for (int v = 0; v < k.height_px; ++v) {
    for (int u = 0; u < k.width_px; ++u) depth.at(u, v) = u < 40 ? 0.5f : 9.0f;
  }
  const FreeSpaceConfig config = placeConfig(0.05f);
  ChangedView bad =
      viewOf(Eigen::Isometry3f::Identity(), {{30, 10, 1.0f}, {50, 30, 1.0f}}, depth, config);
  bad.samples.push_back({10, 30, NAN});   // no surface
  bad.samples.push_back({10, 10, 1.0f});  // no depth kept there
  TsdfMap map(fusionConfig());
  const FreeSpaceStats stats = integrateChangedPlaces({bad}, k, config, place, map);
  EXPECT_EQ(stats.samples, 4u);
  EXPECT_EQ(stats.voxels, 0u);
  EXPECT_EQ(map.blockCount(), 0u);
  ChangedView bad_pose = bad;
  bad_pose.T_W_C.translation().x() = NAN;
  EXPECT_THROW(integrateChangedPlaces({bad_pose}, k, config, place, map), InputError);
  MapConfig coarse;
  coarse.voxel_size_m = 0.05f;
  EXPECT_THROW(integrateChangedPlaces({bad}, k, config, TsdfMap(coarse), map), InputError);
  for (const float radius : {0.0f, NAN, 3.0f}) {
    FreeSpaceConfig bad_config;
    bad_config.place_radius_m = radius;
    EXPECT_THROW(integrateChangedPlaces({}, k, bad_config, place, map), InputError) << radius;
    EXPECT_THROW(keepDepthAround(depth, k, bad_config, bad), InputError) << radius;
  }
  FreeSpaceConfig bad_config;
  bad_config.cell_px = 0;
  EXPECT_THROW(integrateChangedPlaces({}, k, bad_config, place, map), InputError);
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

/// A camera looking down at the floor (z = 0) with box A on it, from exact ray intersections.
/// With `box_there`, the keyframe measures the box and its grid samples on the box are arrived
/// samples (the map holds the floor); without, it measures the floor and its grid samples whose
/// rays met the box are vacated samples, with the box's surface there (the map holds the box).
ChangedView boxView(const Eigen::Vector3f& eye_W, const CameraIntrinsics& k, bool box_there) {
  const Eigen::Isometry3f T_W_C = lookingDown(eye_W);
  const Eigen::AlignedBox3f box = kBoxA.cast<float>();
  std::vector<VacatedSample> samples;
  std::vector<ArrivedSample> arrived;
  DepthImage depth(k.width_px, k.height_px);
  for (int v = 0; v < k.height_px; ++v) {
    for (int u = 0; u < k.width_px; ++u) {
      const Eigen::Vector3f ray_C((u - k.cx_px) / k.fx_px, (v - k.cy_px) / k.fy_px, 1.0f);
      const Eigen::Vector3f dir_W = T_W_C.linear() * ray_C;  // advances 1 in camera z
      const float floor_t = eye_W.z() / -dir_W.z();
      float t_in = 0.0f, t_out = INFINITY;  // slab intersection, t = camera z
      for (int a = 0; a < 3; ++a) {
        const float t0 = (box.min()[a] - eye_W[a]) / dir_W[a];
        const float t1 = (box.max()[a] - eye_W[a]) / dir_W[a];
        t_in = std::max(t_in, std::min(t0, t1));
        t_out = std::min(t_out, std::max(t0, t1));
      }
      const bool meets_box = t_in < t_out && t_in < floor_t;
      depth.at(u, v) = box_there && meets_box ? t_in : floor_t;
      if (u % kCellPx != 2 || v % kCellPx != 2 || !meets_box) continue;  // grid samples only
      if (box_there) {
        arrived.push_back({u, v, t_in});
      } else {
        samples.push_back({u, v, t_in});
      }
    }
  }
  ChangedView view{T_W_C, std::move(samples), DepthTiles(kCellPx), std::move(arrived)};
  keepDepthAround(depth, k, placeConfig(), view);
  return view;
}

/// The floor, and box A when `with_box`, as the demo's change layers hold them (one weight per
/// frame), observed where `observed`.
TsdfMap floorMap(bool with_box, const test::PointTest& observed) {
  const TsdfMap sdf = test::makeSdfMap(
      [&](const Eigen::Vector3d& p) {
        return with_box ? std::min(p.z(), test::boxSdf(p, kBoxA)) : p.z();
      },
      {0, 0, -0.1}, {2, 2, 1.1}, kVoxel, observed);
  TsdfMap constant(fusionConfig());
  for (const auto& [b, block] : sdf.blocks()) constant.allocateBlock(b) = block;
  return constant;
}

/// Unobserved within 0.3 m of box A: a session that fused no frame of its place.
bool awayFromBox(const Eigen::Vector3d& p) { return kBoxA.exteriorDistance(p) > 0.3; }

/// Box A's footprint, up to its top, as an object's box.
void expectBoxA(const Eigen::AlignedBox3f& bbox) {
  for (int a = 0; a < 2; ++a) {
    EXPECT_NEAR(bbox.min()[a], kBoxA.min()[a], 2 * kVoxel) << "axis " << a;
    EXPECT_NEAR(bbox.max()[a], kBoxA.max()[a], 2 * kVoxel) << "axis " << a;
  }
  EXPECT_NEAR(bbox.max().z(), kBoxA.max().z(), 2 * kVoxel);
}

const std::vector<Eigen::Vector3f> kEyes{
    {0.7f, 0.65f, 1.6f}, {0.6f, 0.7f, 1.5f}, {0.8f, 0.6f, 1.7f}};

/// What the reference detector finds of box A when session 0 holds `box_before` (everything
/// observed), session 1 the other state of the box (its layer unobserved within 0.3 m of the box:
/// it fused no frame of that place), and session 1's layer takes `views` unfused: box A's
/// vacated place (box_before) or its arrived surface. Each stat and own evidence go to the
/// caller; the objects are those of the session where the box stood.
std::vector<DiscoveredObject> objectsFromUnfusedViews(bool box_before,
                                                      const std::vector<ChangedView>& views,
                                                      FreeSpaceStats& stats, VoxelSet& own) {
  const auto everywhere = [](const Eigen::Vector3d&) { return true; };
  ChangeConfig config;
  config.min_weight = 3.0f;  // the demo's: three frames with constant weights
  ChangeDetector detector(floorMap(box_before, everywhere).config(), config);
  detector.endSession(detector.addSessionMap(floorMap(box_before, everywhere)));
  const int second = detector.addSessionMap(floorMap(!box_before, awayFromBox));
  TsdfMap layer = detector.sessionMap(second);
  // The place: what session 0 last observed.
  stats = integrateChangedPlaces(views, smallCamera(), placeConfig(), detector.sessionMap(0), layer,
                                 nullptr, &own);
  detector.replaceSessionMap(second, layer);
  detector.endSession(second);
  return sessionObjects(detector, box_before ? 0 : second);
}

TEST(FreeSpace, ThreeUnfusedViewsOfAVacatedPlaceLetTheDetectorFindTheEarlierInstance) {
  // Session 0: box A on the floor. Session 1: the box is gone.
  std::vector<ChangedView> views;
  for (const Eigen::Vector3f& eye_W : kEyes) views.push_back(boxView(eye_W, smallCamera(), false));
  for (const std::size_t view_count : {0u, 2u, 3u}) {
    FreeSpaceStats stats;
    VoxelSet own;
    const auto objects =
        objectsFromUnfusedViews(true, {views.begin(), views.begin() + view_count}, stats, own);
    EXPECT_EQ(stats.voxels > 0, view_count > 0);
    if (view_count < 3) {
      EXPECT_TRUE(objects.empty()) << view_count << " views leave the place below min_weight";
      continue;
    }
    ASSERT_EQ(objects.size(), 1u);
    expectBoxA(objects[0].bbox);  // the box as the earlier session held it
  }
}

TEST(FreeSpace, ThreeUnfusedViewsOfAnArrivedObjectLetTheDetectorFindIt) {
  // Session 0: the floor alone. Session 1: box A stands on it.
  std::vector<ChangedView> views;
  for (const Eigen::Vector3f& eye_W : kEyes) views.push_back(boxView(eye_W, smallCamera(), true));
  for (const std::size_t view_count : {0u, 2u, 3u}) {
    FreeSpaceStats stats;
    VoxelSet own;
    const auto objects =
        objectsFromUnfusedViews(false, {views.begin(), views.begin() + view_count}, stats, own);
    EXPECT_EQ(stats.samples, 0u);
    EXPECT_EQ(stats.voxels > 0, view_count > 0);
    EXPECT_EQ(own.empty(), view_count == 0)
        << "the box's inside contradicts the floor's free space";
    if (view_count < 3) {
      EXPECT_TRUE(objects.empty()) << view_count << " views leave the box below min_weight";
      continue;
    }
    ASSERT_EQ(objects.size(), 1u);
    expectBoxA(objects[0].bbox);
  }
}

}  // namespace
}  // namespace strata::change

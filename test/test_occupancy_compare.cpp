// Occupancy layer against the TSDF and the true scene: surface position and
// completeness on the analytic scene (exact depth) and a simulated room session (sensor noise).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "strata/sim/sim_setup.h"
#include "strata/occupancy/eval/occupancy_compare.h"
#include "strata/occupancy/eval/occupancy_nearest.h"
#include "fusion_fixture.h"
#include "strata/occupancy/occupancy_reference.h"
#include "strata/mesh/mesh_metrics.h"
#include "strata/sim/analytic_dataset.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata {
namespace {

constexpr float kVoxelM = 0.05f;

CameraIntrinsics halfCamera() {  // half of 640 x 480: enough rays per voxel at room range
  CameraIntrinsics in;
  in.width_px = 320;
  in.height_px = 240;
  in.fx_px = in.fy_px = 262.5f;
  in.cx_px = 159.5f;
  in.cy_px = 119.5f;
  return in;
}

eval::OccupancyComparisonSetup setup(std::size_t frames) {
  eval::OccupancyComparisonSetup s;
  s.map.voxel_size_m = kVoxelM;
  s.map.max_depth_m = 5.0f;
  s.occupancy = OccupancyConfig::forMap(s.map);
  s.frames = frames;
  s.run_reference = true;
  return s;
}

void print(const char* what, const eval::OccupancyTsdfComparison& c) {
  std::printf(
      "[ occupancy vs tsdf ] %s: %zu frames, %zu truth points\n"
      "  occupancy: %zu occupied voxels, error mean %.4f median %.4f p95 %.4f m, complete %.3f\n"
      "  tsdf mesh: %zu vertices, error mean %.4f median %.4f p95 %.4f m, complete %.3f\n",
      what, c.frames, c.truth_points, c.occupied_voxels, c.occupancy_error.mean_m,
      c.occupancy_error.median_m, c.occupancy_error.p95_m, c.occupancy_completeness,
      c.mesh_vertices, c.tsdf_error.mean_m, c.tsdf_error.median_m, c.tsdf_error.p95_m,
      c.tsdf_completeness);
}

void expectDeviceMatchedReference(const eval::OccupancyTsdfComparison& c) {
  EXPECT_GT(c.device_vs_reference.compared, 0u);
  EXPECT_EQ(c.device_vs_reference.class_mismatches, 0u);
  EXPECT_GE(c.device_vs_reference.shareWithin(), 0.999);
}

TEST(OccupancyVsTsdf, AnalyticSceneWithExactDepth) {
  sim::AnalyticDatasetConfig data;
  data.frame_count = 10;
  data.intrinsics = halfCamera();
  data.render_color = false;
  const sim::AnalyticDataset dataset(data);
  const auto truth = [&](const Eigen::Vector3d& p) { return dataset.scene().signedDistance(p); };
  const auto c = eval::compareOccupancyWithTsdf(
      test::sharedContext(), dataset, [&](std::size_t i) { return dataset.load(i); }, truth,
      setup(0));
  print("analytic scene, 5 cm", c);
  expectDeviceMatchedReference(c);
  // Exact depth: an occupied voxel was hit, so it holds a surface point and its centre is at most
  // half a voxel diagonal from the surface.
  EXPECT_LE(c.occupancy_error.p95_m, 0.5 * std::sqrt(3.0) * kVoxelM + 1e-4);
  EXPECT_GT(c.occupancy_completeness, 0.95);
  EXPECT_GT(c.tsdf_completeness, 0.95);
  // The TSDF interpolates the zero crossing; occupancy keeps the voxel grid's quantisation.
  EXPECT_LT(c.tsdf_error.median_m, c.occupancy_error.median_m);
}

TEST(OccupancyVsTsdf, EveryOccupiedVoxelHoldsTheTrueSurfaceAtExactDepth) {
  sim::AnalyticDatasetConfig data;
  data.frame_count = 6;
  data.intrinsics = halfCamera();
  data.render_color = false;
  const sim::AnalyticDataset dataset(data);
  OccupancyConfig config;
  OccupancyMap map(kVoxelM);
  for (std::size_t i = 0; i < dataset.size(); ++i) {
    const RgbdFrame frame = dataset.load(i);
    integrateOccupancyReference(frame.depth, FrameCamera::from(dataset.intrinsics(), frame.T_W_C),
                                config, map);
  }
  const auto centres = occupiedVoxelCentres(map, config.logOdds());
  ASSERT_GT(centres.size(), 1000u);
  const double half_diagonal_m = 0.5 * std::sqrt(3.0) * kVoxelM;
  std::size_t off_surface = 0;
  for (const Eigen::Vector3f& c : centres) {
    off_surface += std::abs(dataset.scene().signedDistance(Eigen::Vector3d(c.cast<double>()))) >
                           half_diagonal_m + 1e-4
                       ? 1
                       : 0;
  }
  EXPECT_EQ(off_surface, 0u);
  const Mesh cubes = eval::occupiedVoxelMesh(map, config.logOdds());
  EXPECT_EQ(cubes.triangles.size(), centres.size() * 12);
  EXPECT_TRUE(analyzeTopology(cubes).isClosedOriented());
}

TEST(OccupancyVsTsdf, SimulatedRoomSessionWithSensorNoise) {
  sim::SimSessionConfig session_config = sim::sessionConfig(30.0, 10, true, false);
  session_config.camera.intrinsics = halfCamera();
  const sim::SimSessionDataset session(sim::loadWorld(sim::findWorld("room"), 0, 0), 0,
                                       session_config);
  const auto truth_frame = [&](std::size_t i) {
    RgbdFrame frame;
    frame.depth = session.render(i).depth_true;
    frame.T_W_C = session.truePoses()[i];
    return frame;
  };
  const auto truth = [&](const Eigen::Vector3d& p) {
    return static_cast<double>(session.scene().signedDistance(p.cast<float>()));
  };
  const auto c =
      eval::compareOccupancyWithTsdf(test::sharedContext(), session, truth_frame, truth, setup(0));
  print("room session 0, noise on, 5 cm", c);
  expectDeviceMatchedReference(c);
  EXPECT_LT(c.occupancy_error.median_m, kVoxelM);
  EXPECT_LT(c.tsdf_error.median_m, kVoxelM);
  EXPECT_GT(c.occupancy_completeness, 0.9);
  EXPECT_GT(c.tsdf_completeness, 0.9);
}

TEST(OccupancyNearest, TriangleGridMatchesClosestPointsOfATriangle) {
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  mesh.triangles = {{0, 1, 2}};
  const eval::TriangleGrid grid(mesh, 0.5f);
  EXPECT_NEAR(grid.nearestWithin({0.2f, 0.2f, 0.3f}), 0.3, 1e-6);    // above the face
  EXPECT_NEAR(grid.nearestWithin({-0.3f, -0.4f, 0.0f}), 0.5, 1e-6);  // nearest to a vertex
  EXPECT_NEAR(grid.nearestWithin({0.6f, 0.6f, 0.0f}), std::sqrt(0.02), 1e-6);  // hypotenuse
  EXPECT_TRUE(std::isinf(grid.nearestWithin({0.2f, 0.2f, 0.6f})));             // beyond the radius
  const eval::PointGrid points({{0, 0, 0}, {1, 1, 1}}, 0.5f);
  EXPECT_NEAR(points.nearestWithin({0.9f, 1.0f, 1.0f}), 0.1, 1e-6);
  EXPECT_TRUE(std::isinf(points.nearestWithin({0.5f, 0.5f, 0.5f})));
}

}  // namespace
}  // namespace strata

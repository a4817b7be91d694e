// Exploration ground truth on the room world: reachable space against the room's volume less its
// furniture (from the world's own shapes) and against a voxel-by-voxel evaluation, the explored
// fraction of maps built from the truth, and the clearance of points at known distances.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "strata/core/error.h"
#include "strata/explore/reachable_space.h"
#include "strata/sim/world/shape_mesh.h"
#include "strata/sim/world/world.h"
#include "strata/sim/world/world_paths.h"

namespace strata::explore {
namespace {

const sim::World& room() {
  static const sim::World world = sim::World::load(sim::findWorld("room"));
  return world;
}

const sim::WorldScene& roomScene() {
  static const std::unique_ptr<sim::WorldScene> scene = room().buildScene(0);
  return *scene;
}

// Above the table, below the ceiling, clear of the bookshelf and the lamp.
const Eigen::Vector3d kStart_W(2.5, 2.0, 2.0);

/// Volume, area and area on the floor (z = 0) of a closed triangle mesh (divergence theorem).
void volumeAndArea(const Mesh& mesh, double* volume_m3, double* area_m2, double* floor_m2) {
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]].cast<double>();
    const Eigen::Vector3d b = mesh.vertices[t[1]].cast<double>();
    const Eigen::Vector3d c = mesh.vertices[t[2]].cast<double>();
    *volume_m3 += a.dot(b.cross(c)) / 6.0;
    const double area = 0.5 * (b - a).cross(c - a).norm();
    *area_m2 += area;
    if (std::max({a.z(), b.z(), c.z()}) < 1e-6) *floor_m2 += area;
  }
}

TEST(ExplorationTruth, ReachableSpaceIsTheRoomLessItsFurniture) {
  const double voxel_m = 0.05;
  const ReachableSpace space =
      computeReachableSpace(roomScene(), room().bounds(), kStart_W, voxel_m);
  // Free space keeps half a voxel from every surface: the room shrinks by half a voxel on each
  // side, each part of the furniture grows by its area x half a voxel (Steiner's formula, to
  // first order), less its footprint on the floor (that layer is gone already).
  const double room_m3 = (5.0 - voxel_m) * (4.0 - voxel_m) * (2.5 - voxel_m);
  double furniture_m3 = 0.0;
  const auto add = [&](const sim::ShapeSpec& shape) {
    for (const Mesh& part : sim::shapeParts(shape)) {
      double volume_m3 = 0.0, area_m2 = 0.0, floor_m2 = 0.0;
      volumeAndArea(part, &volume_m3, &area_m2, &floor_m2);
      furniture_m3 += volume_m3 + 0.5 * voxel_m * (area_m2 - floor_m2);
    }
  };
  for (const sim::ObjectSpec& element : room().spec().static_elements) add(element.shape);
  for (const sim::ObjectState& object : room().session(0).objects) {
    if (object.present) add(room().object(object.id).shape);
  }
  const double expected_m3 = room_m3 - furniture_m3;
  EXPECT_NEAR(space.volume_m3, expected_m3, 0.015 * expected_m3)
      << "room " << room_m3 << " m3, furniture " << furniture_m3 << " m3";
  EXPECT_EQ(space.reachable_count, space.free_count);  // one room: all free space is connected
}

TEST(ExplorationTruth, CellsAgreeWithVoxelByVoxelTruthAndTheOutsideIsUnreachable) {
  // Bounds beyond the walls, not aligned with them: free space outside the room is unreachable.
  const double voxel_m = 0.1;
  Eigen::AlignedBox3d bounds = room().bounds();
  bounds.min() -= Eigen::Vector3d(0.43, 0.37, 0.31);
  bounds.max() += Eigen::Vector3d(0.29, 0.33, 0.41);
  const ReachableSpace space = computeReachableSpace(roomScene(), bounds, kStart_W, voxel_m);
  std::size_t free = 0, reachable_inside = 0;
  for (int z = 0; z < space.dims.z(); ++z) {
    for (int y = 0; y < space.dims.y(); ++y) {
      for (int x = 0; x < space.dims.x(); ++x) {
        const Eigen::Vector3d c = space.center(x, y, z);
        const bool is_free = roomScene().distanceToSurface(c) > 0.5 * voxel_m &&
                             !roomScene().occupied(c.cast<float>());
        free += is_free ? 1 : 0;
        const bool in_room = (c.array() > 0.0).all() && c.x() < 5.0 && c.y() < 4.0 && c.z() < 2.5;
        if (space.isReachable(x, y, z)) {
          EXPECT_TRUE(is_free && in_room) << c.transpose();
          ++reachable_inside;
        }
      }
    }
  }
  EXPECT_EQ(space.free_count, free);
  EXPECT_GT(space.free_count, space.reachable_count + 10000);  // the shell of air outside
  EXPECT_GT(reachable_inside, 40000u);
}

TEST(ExplorationTruth, ExploredFractionCountsObservedReachableVoxels) {
  const ReachableSpace space = computeReachableSpace(roomScene(), room().bounds(), kStart_W, 0.1);
  MapConfig config;
  config.voxel_size_m = 0.04f;  // another voxel size than the grid's
  TsdfMap map(config);
  EXPECT_EQ(exploredFraction(space, map, 1e-3f), 0.0);
  // Observe every map voxel with its centre at x < 2.5 (weight 1), the rest barely (1e-4).
  std::size_t reachable_west = 0;
  for (int z = 0; z < space.dims.z(); ++z) {
    for (int y = 0; y < space.dims.y(); ++y) {
      for (int x = 0; x < space.dims.x(); ++x) {
        if (!space.isReachable(x, y, z)) continue;
        const Eigen::Vector3d c = space.center(x, y, z);
        const GlobalVoxelIndex v = (c / config.voxel_size_m).array().floor().cast<int>();
        const bool west = voxelCenter(v, config.voxel_size_m).x() < 2.5f;
        map.allocateVoxel(v).weight = west ? 1.0f : 1e-4f;
        reachable_west += west ? 1 : 0;
      }
    }
  }
  const double fraction = exploredFraction(space, map, 1e-3f);
  EXPECT_DOUBLE_EQ(fraction, double(reachable_west) / double(space.reachable_count));
  EXPECT_NEAR(fraction, 0.5, 0.05);  // the furniture stands unevenly
  EXPECT_DOUBLE_EQ(exploredFraction(space, map, 1e-5f), 1.0);
}

TEST(ExplorationTruth, ClearanceIsTheDistanceToTheNearestSurface) {
  // 0.25 m from the wall y = 0, 0.5 m below the ceiling, far above every object.
  const std::vector<Eigen::Vector3d> path = {kStart_W, {2.5, 0.25, 2.0}, {2.5, 1.0, 2.0}};
  EXPECT_NEAR(minClearanceAlong(roomScene(), path), 0.25, 1e-6);
  EXPECT_NEAR(minClearanceAlong(roomScene(), {{2.5, 2.0, 2.3}}), 0.2, 1e-6);  // the ceiling
  EXPECT_TRUE(std::isinf(minClearanceAlong(roomScene(), {})));
}

TEST(ExplorationTruth, TheDeadEndCorridorIsReachedThroughTheJunctionOnly) {
  const sim::World world = sim::World::load(sim::findWorld("deadend"));
  const auto scene = world.buildScene(0);
  const double voxel_m = 0.1;
  // A start in the hall at the junction (worlds/deadend.yaml).
  const ReachableSpace space =
      computeReachableSpace(*scene, world.bounds(), {9.0, 4.0, 1.2}, voxel_m);
  // The bounds hold the air outside the building beside the corridor: free but unreachable.
  EXPECT_GT(space.free_count, space.reachable_count + 200000);
  std::size_t corridor = 0, behind_partition = 0;
  bool end_reached = false;
  for (int z = 0; z < space.dims.z(); ++z) {
    for (int y = 0; y < space.dims.y(); ++y) {
      for (int x = 0; x < space.dims.x(); ++x) {
        if (!space.isReachable(x, y, z)) continue;
        const Eigen::Vector3d c = space.center(x, y, z);
        corridor += c.x() > 10.1 ? 1 : 0;
        behind_partition += c.x() < 7.5 ? 1 : 0;
        end_reached = end_reached || c.x() > 31.0;
      }
    }
  }
  const double voxel_m3 = std::pow(voxel_m, 3);
  // Corridor 22 x 2 x 2.5 m less half a voxel on every side and the shelf at its end.
  EXPECT_NEAR(corridor * voxel_m3, 21.9 * 1.9 * 2.4 - 1.0, 1.5);
  EXPECT_TRUE(end_reached);
  // Most of the hall lies behind the partition, more than the corridor holds.
  EXPECT_GT(behind_partition, corridor);
}

TEST(ExplorationTruth, BadInputIsAnInputError) {
  const Eigen::AlignedBox3d bounds = room().bounds();
  EXPECT_THROW(computeReachableSpace(roomScene(), bounds, kStart_W, 0.0), InputError);
  EXPECT_THROW(computeReachableSpace(roomScene(), Eigen::AlignedBox3d(), kStart_W, 0.1),
               InputError);
  EXPECT_THROW(computeReachableSpace(roomScene(), bounds, {9.0, 2.0, 1.0}, 0.1), InputError);
  try {
    computeReachableSpace(roomScene(), bounds, {2.5, 2.0, 0.01}, 0.1);  // on the floor
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not in free space"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace strata::explore

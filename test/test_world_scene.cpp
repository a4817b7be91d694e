// World scenes: ray casts, signed distance and occupancy against analytic truth, per-session
// scenes, closed outward meshes.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "strata/mesh/mesh_metrics.h"
#include "strata/sim/world/world.h"
#include "strata/sim/world/world_paths.h"
#include "world_test_scenes.h"

namespace strata::sim {
namespace {

using test::analyticBoxRoomSdf;
using test::boxRoomYaml;
using test::kShippedWorlds;

TEST(World, RaysHitFloorAndBoxFaces) {
  for (const double yaw : {0.0, 30.0}) {
    SCOPED_TRACE(yaw);
    const World world = World::fromYaml(boxRoomYaml(yaw), "box_room.yaml");
    const auto scene = world.buildScene(0);
    const Eigen::Matrix3f R =
        Eigen::AngleAxisf(static_cast<float>(yaw * M_PI / 180.0), Eigen::Vector3f::UnitZ())
            .toRotationMatrix();
    const Eigen::Vector3f centre(2.0f, 1.5f, 0.25f);
    std::vector<Ray> rays = {
        {Eigen::Vector3f(0.7f, 0.6f, 1.2f), -Eigen::Vector3f::UnitZ()},                  // floor
        {centre + R * Eigen::Vector3f(-1.3f, 0, 0), R * Eigen::Vector3f::UnitX()},       // -x face
        {centre + R * Eigen::Vector3f(0, 0.9f, 0.1f), -(R * Eigen::Vector3f::UnitY())},  // +y face
        {Eigen::Vector3f(2.0f, 1.5f, 2.0f), -Eigen::Vector3f::UnitZ()},                  // box top
        {Eigen::Vector3f(1.0f, 1.0f, 1.0f), Eigen::Vector3f::UnitZ(), 0.5f},  // ends short
    };
    std::vector<RayHit> hits;
    scene->intersect(rays, hits);
    ASSERT_EQ(hits.size(), rays.size());
    EXPECT_NEAR(hits[0].t_m, 1.2f, 1e-5f);
    EXPECT_EQ(hits[0].object_id, kStaticObjectId);
    EXPECT_TRUE(hits[0].normal_W.isApprox(Eigen::Vector3f::UnitZ(), 1e-5f));
    EXPECT_EQ(hits[0].material.albedo, (std::array<std::uint8_t, 3>{10, 20, 30}));
    EXPECT_NEAR(hits[1].t_m, 1.0f, 1e-5f);
    EXPECT_EQ(hits[1].object_id, 1);
    EXPECT_TRUE(hits[1].normal_W.isApprox(-(R * Eigen::Vector3f::UnitX()), 1e-5f));
    EXPECT_EQ(hits[1].material.albedo, (std::array<std::uint8_t, 3>{200, 60, 40}));
    EXPECT_FLOAT_EQ(hits[1].material.reflectivity, 0.5f);
    EXPECT_NEAR(hits[2].t_m, 0.7f, 1e-5f);
    EXPECT_TRUE(hits[2].normal_W.isApprox(R * Eigen::Vector3f::UnitY(), 1e-5f));
    EXPECT_NEAR(hits[3].t_m, 1.5f, 1e-5f);
    EXPECT_EQ(hits[3].object_id, 1);
    EXPECT_FALSE(hits[4].hit());
  }
}

TEST(World, BatchedIntersectMatchesSingleRays) {
  const World world = World::load(defaultWorldPath());
  const auto scene = world.buildScene(2, WorldScene::Config{3, 64});
  std::mt19937 rng(5);  // test inputs only; the world itself never uses std distributions
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Ray> rays(3000);
  for (Ray& ray : rays) {
    // One draw per statement, last coordinate first: the order of f(u(rng), u(rng)) is open in C++.
    const float oz = u(rng), oy = u(rng), ox = u(rng);
    ray.origin_W = Eigen::Vector3f(2.5f + ox, 2.0f + oy, 1.2f + 0.5f * oz);
    const float dz = u(rng), dy = u(rng), dx = u(rng);
    ray.direction_W = Eigen::Vector3f(dx, dy, dz).normalized();
  }
  std::vector<RayHit> batch, single;
  scene->intersect(rays, batch);
  for (std::size_t i = 0; i < rays.size(); i += 97) {
    scene->intersect({rays[i]}, single);
    EXPECT_EQ(single[0].object_id, batch[i].object_id);
    EXPECT_EQ(single[0].t_m, batch[i].t_m);
  }
  for (const RayHit& hit : batch) EXPECT_TRUE(hit.hit());  // a closed room: every ray hits
}

TEST(World, SignedDistanceMatchesAnalyticBoxRoom) {
  const World world = World::fromYaml(boxRoomYaml(0.0), "box_room.yaml");
  const auto scene = world.buildScene(0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> ux(0.01, 3.99), uy(0.01, 2.99), uz(0.01, 2.49);
  int checked = 0;
  for (int i = 0; i < 400; ++i) {
    const double z = uz(rng), y = uy(rng), x = ux(rng);  // one draw each, in a fixed order
    const Eigen::Vector3d p(x, y, z);
    const Eigen::Vector3f pf = p.cast<float>();
    const double expected = analyticBoxRoomSdf(pf.cast<double>());
    if (std::abs(expected) < 1e-3) continue;  // on a surface the sign is a coin toss
    EXPECT_NEAR(scene->signedDistance(pf), expected, 1e-5) << p.transpose();
    EXPECT_EQ(scene->occupied(pf), expected < 0.0) << p.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 350);
  // Points inside the box, where the nearest face is known.
  EXPECT_NEAR(scene->signedDistance({2.05f, 1.5f, 0.3f}), -0.2f, 1e-5f);
  EXPECT_NEAR(scene->signedDistance({2.2f, 1.45f, 0.25f}), -0.1f, 1e-5f);
}

TEST(World, OccupancyOfSolids) {
  const World world = World::fromYaml(boxRoomYaml(30.0), "box_room.yaml");
  const auto scene = world.buildScene(0);
  EXPECT_TRUE(scene->occupied({2.0f, 1.5f, 0.25f}));    // box centre
  EXPECT_TRUE(scene->occupied({2.1f, 1.6f, 0.45f}));    // inside the turned box
  EXPECT_FALSE(scene->occupied({1.0f, 1.0f, 1.0f}));    // free space
  EXPECT_TRUE(scene->occupied({-0.05f, 1.5f, 1.0f}));   // in the west wall
  EXPECT_TRUE(scene->occupied({1.0f, 1.0f, -0.05f}));   // in the floor slab
  EXPECT_TRUE(scene->occupied({1.0f, 1.0f, 2.55f}));    // in the ceiling slab
  EXPECT_FALSE(scene->occupied({-1.0f, -1.0f, 1.0f}));  // outside the building
  EXPECT_LT(scene->signedDistance({-0.05f, 1.5f, 1.0f}), 0.0f);
  EXPECT_NEAR(scene->signedDistance({-1.0f, 1.5f, 1.0f}), 0.9f, 1e-5f);
}

TEST(World, SceneFollowsTheSessionTruth) {
  for (const char* name : kShippedWorlds) {
    SCOPED_TRACE(name);
    const World world = World::load(findWorld(name));
    for (int s = 0; s < world.sessionCount(); ++s) {
      const auto scene = world.buildScene(s);
      std::vector<Ray> rays;
      std::vector<const ObjectState*> objects;
      for (const ObjectState& object : world.session(s).objects) {
        if (object.shape == ShapeKind::kMesh) continue;  // a mesh may have no top at its centre
        const Eigen::Vector3f above(object.at_m.x(), object.at_m.y(), 2.0f);
        rays.push_back({above, -Eigen::Vector3f::UnitZ()});
        objects.push_back(&object);
      }
      std::vector<RayHit> hits;
      scene->intersect(rays, hits);
      for (std::size_t i = 0; i < rays.size(); ++i) {
        if (objects[i]->present) {
          EXPECT_EQ(hits[i].object_id, objects[i]->id) << objects[i]->name << " session " << s;
          // Straight down onto the centre: the seat of a chair, the top of anything else.
          const double top = world.object(objects[i]->id).shape.size_m.z() *
                             (objects[i]->shape == ShapeKind::kChair ? 0.5 : 1.0);
          EXPECT_NEAR(hits[i].t_m, 2.0 - top, 1e-4) << objects[i]->name;
        } else {
          EXPECT_NE(hits[i].object_id, objects[i]->id) << objects[i]->name << " session " << s;
        }
      }
    }
  }
}

/// Signed volume by the divergence theorem: positive when the triangles face outwards.
double signedVolume(const Mesh& mesh) {
  double volume = 0.0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    volume += mesh.vertices[t[0]].cast<double>().dot(
                  mesh.vertices[t[1]].cast<double>().cross(mesh.vertices[t[2]].cast<double>())) /
              6.0;
  }
  return volume;
}

TEST(World, MeshesAreClosedAndFaceOutwards) {
  const World world = World::load(findWorld("office"));
  for (int id = 1; id <= world.objectCount(); ++id) {
    if (world.object(id).shape.kind == ShapeKind::kMesh) continue;  // file meshes: as given
    const Mesh mesh = world.objectMesh(id);
    SCOPED_TRACE(world.object(id).name);
    EXPECT_TRUE(analyzeTopology(mesh).isClosedOriented());
    EXPECT_GT(signedVolume(mesh), 0.0);
  }
  const Mesh static_mesh = world.staticMesh();
  EXPECT_TRUE(analyzeTopology(static_mesh).isClosedOriented());
  EXPECT_GT(signedVolume(static_mesh), 0.0);
  const Mesh session = world.sessionMesh(1);
  EXPECT_GT(session.triangles.size(), static_mesh.triangles.size());
  EXPECT_EQ(session.colors.size(), session.vertices.size());
  // Box of 0.6 x 0.4 x 0.5: exact volume.
  const World box = World::fromYaml(boxRoomYaml(0.0), "box_room.yaml");
  EXPECT_NEAR(signedVolume(box.objectMesh(1)), 0.6 * 0.4 * 0.5, 1e-6);
}

}  // namespace
}  // namespace strata::sim

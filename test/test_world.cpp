// Synthetic multi-session worlds: world files, seeded layouts, meshes, Embree scene ground truth.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "strata/core/error.h"
#include "strata/mesh/mesh_metrics.h"
#include "strata/sim/world/footprint.h"
#include "strata/sim/world/ground_truth.h"
#include "strata/sim/world/mesh_file.h"
#include "strata/sim/world/world.h"
#include "strata/sim/world/world_paths.h"
#include "test_utils.h"
#include "world_test_scenes.h"

namespace strata::sim {
namespace {

namespace fs = std::filesystem;
using test::analyticBoxRoomSdf;
using test::boxRoomYaml;
using test::kShippedWorlds;

std::string errorOf(const std::string& yaml) {
  try {
    World::fromYaml(yaml, "bad.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(World, ParsesShippedWorlds) {
  for (const char* name : kShippedWorlds) {
    SCOPED_TRACE(name);
    const World world = World::load(findWorld(name));
    EXPECT_EQ(world.name(), name);
    EXPECT_GE(world.objectCount(), 1);
    EXPECT_FALSE(world.staticMesh().empty());
  }
  for (const char* name : test::kMultiSessionWorlds) {
    SCOPED_TRACE(name);
    const World world = World::load(findWorld(name));
    EXPECT_EQ(world.sessionCount(), 5);
    EXPECT_GE(world.objectCount(), 8);
  }
  const World room = World::load(defaultWorldPath());
  EXPECT_EQ(room.name(), "room");
  const Eigen::Vector3d size = room.bounds().sizes();
  EXPECT_NEAR(size.x(), 5.2, 1e-6);  // interior 5 x 4 x 2.5 plus 0.1 m walls, floor, ceiling
  EXPECT_NEAR(size.y(), 4.2, 1e-6);
  EXPECT_NEAR(size.z(), 2.7, 1e-6);
  for (int s = 0; s < room.sessionCount(); ++s) {
    EXPECT_GE(room.session(s).presentCount(), 8);
    EXPECT_LE(room.session(s).presentCount(), 15);
  }
}

TEST(World, MalformedFilesNameLineAndField) {
  const std::string head = "rooms:\n  - {min: [0, 0], max: [4, 3], height: 2.5}\nobjects:\n";
  struct Case {
    std::string yaml, expected;
  };
  const std::vector<Case> cases = {
      {head + "  - {type: sphere, size: [1, 1, 1]}\n",
       "bad.yaml:4: objects[0].type: unknown type 'sphere'"},
      {head + "  - {name: a, type: box}\n", "bad.yaml:4: objects[0].size: missing"},
      {head + "  - name: a\n    type: box\n    size: [1, 2]\n",
       "bad.yaml:6: objects[0].size: expected 3 numbers, got 2"},
      {head + "  - {type: box, size: [1, -2, 1]}\n",
       "bad.yaml:4: objects[0].size: every size must be positive"},
      {head + "  - name: a\n    type: box\n    size: [1, 1, 1]\n    albdo: [1, 2, 3]\n",
       "bad.yaml:7: objects[0].albdo: unknown key (did you mean 'albedo'?)"},
      {head + "  - {type: box, size: [1, x, 1]}\n",
       "bad.yaml:4: objects[0].size[1]: expected a number, got 'x'"},
      {head + "  - {type: cylinder, radius: 0.2, height: 1, size: [1, 1, 1]}\n",
       "bad.yaml:4: objects[0].size: unknown key"},
      {head + "  - {type: box, size: [1, 1, 1], albedo: [1, 2, 300]}\n",
       "bad.yaml:4: objects[0].albedo[2]: must be in [0, 255]"},
      {"rooms:\n  - {min: [0, 0], max: [0, 3], height: 2.5}\nobjects: []\n",
       "bad.yaml:2: rooms[0].max: must exceed min"},
      // The limits of world_spec.h, each just over.
      {"rooms:\n  - {min: [0, 0], max: [200.5, 3], height: 2.5}\nobjects: []\n",
       "bad.yaml:2: rooms[0].max: a room side may be at most 200 m"},
      {"rooms:\n  - {min: [0, 0], max: [4, 3], height: 50.5}\nobjects: []\n",
       "bad.yaml:2: rooms[0].height: may be at most 50 m"},
      {"rooms:\n  - {min: [1000.5, 0], max: [1004, 3], height: 2.5}\nobjects: []\n",
       "bad.yaml:2: rooms[0].min: every coordinate must be within 1000 m"},
      {"seed: 1\nrooms: [{min: [0, 0], max: [4, 3], height: 2.5}]\n"
       "objects: [{type: box, size: [1, 1, 1]}]\nchanges:\n  move_probability: 1.5\n",
       "bad.yaml:5: changes.move_probability: must be in [0, 1]"},
      {"rooms: [{min: [0, 0], max: [4, 3], height: 2.5}]\nobjects: [{type: box, size: [1, 1, 1]]\n",
       "bad.yaml:2: YAML syntax error"},
      {"rooms: [{min: [0, 0], max: [4, 3], height: 2.5}]\npool:\n"
       "  - {type: box, size: [1, 1, 1], at: [1, 1]}\n",
       "bad.yaml:3: pool[0].at: pool objects are placed by the seed"},
      {"rooms: [{min: [0, 0], max: [4, 3], height: 2.5}]\nsessions: 3\nsessions: 4\n",
       "bad.yaml:3: sessions: given twice"},
      {"rooms: [{min: [0, 0], max: [4, 3], height: 2.5}]\nsesions: 3\n",
       "bad.yaml:2: sesions: unknown key (did you mean 'sessions'?)"},
      {"rooms: [{min: [0, 0], max: [4, 3], height: 2.5}]\ndoors: [{at: [2, 1.5]}]\n"
       "objects: [{type: box, size: [1, 1, 1]}]\n",
       "bad.yaml:2: doors[0].at: lies in no wall"},
      {head + "  - {name: a, type: box, size: [1, 1, 1], at: [1, 1]}\n"
              "  - {name: b, type: box, size: [1, 1, 1], at: [1.5, 1]}\n",
       "bad.yaml:5: object 'b': its given pose overlaps a"},
  };
  for (const Case& c : cases) {
    const std::string message = errorOf(c.yaml);
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "expected '" << c.expected << "' in '" << message << "'";
  }
}

TEST(World, LoadErrorsNameTheFile) {
  EXPECT_THROW(World::load("/nonexistent/world.yaml"), InputError);
  EXPECT_THROW(findWorld("no_such_world"), InputError);
  const World room = World::load(defaultWorldPath());
  EXPECT_THROW(room.session(room.sessionCount()), InputError);
  EXPECT_THROW(room.objectMesh(0), InputError);
}

TEST(World, SameSeedSameTruthAndFilesDifferentSeedDifferentLayout) {
  const World a = World::load(defaultWorldPath());
  const World b = World::load(defaultWorldPath());
  const World c = World::load(defaultWorldPath(), World::Options{99, std::nullopt});
  bool differs = false;
  for (int s = 0; s < a.sessionCount(); ++s) {
    for (std::size_t i = 0; i < a.session(s).objects.size(); ++i) {
      const ObjectState& x = a.session(s).objects[i];
      const ObjectState& y = b.session(s).objects[i];
      EXPECT_EQ(x.present, y.present);
      EXPECT_EQ(x.T_W_O.matrix(), y.T_W_O.matrix());
      EXPECT_EQ(x.since_previous, y.since_previous);
      const ObjectState& z = c.session(s).objects[i];
      differs = differs || z.present != x.present || !z.T_W_O.isApprox(x.T_W_O);
    }
  }
  EXPECT_TRUE(differs) << "seed 99 gave the same layout as seed 7";

  const fs::path dir_a = strata::test::freshTempDir("world_gt_a");
  const fs::path dir_b = strata::test::freshTempDir("world_gt_b");
  writeGroundTruth(a, dir_a.string());
  writeGroundTruth(b, dir_b.string());
  int files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(dir_a)) {
    if (!entry.is_regular_file()) continue;
    const fs::path relative = fs::relative(entry.path(), dir_a);
    EXPECT_EQ(strata::test::readText(entry.path()), strata::test::readText(dir_b / relative)) << relative;
    ++files;
  }
  EXPECT_GT(files, 5 * 3);
  const std::string json = strata::test::readText(dir_a / "session_1" / "objects.json");
  EXPECT_NE(json.find("\"changed_since_previous\""), std::string::npos);
  EXPECT_NE(json.find("\"T_W_O\""), std::string::npos);
  fs::remove_all(dir_a);
  fs::remove_all(dir_b);
}

TEST(World, EverySessionChangesAndNothingOverlaps) {
  for (const char* name : kShippedWorlds) {
    SCOPED_TRACE(name);
    const World world = World::load(findWorld(name));
    for (int s = 0; s < world.sessionCount(); ++s) {
      const SessionTruth& truth = world.session(s);
      if (s > 0) {
        EXPECT_GE(truth.changedIds().size(), 1u) << "session " << s;
      }
      std::vector<Footprint> placed;
      for (const ObjectState& object : truth.objects) {
        if (!object.present) continue;
        const Eigen::Vector2d half = 0.5 * world.object(object.id).shape.size_m.head<2>();
        const Footprint f = makeFootprint(half, object.at_m, object.yaw_deg);
        for (const Footprint& other : placed) {
          EXPECT_FALSE(overlaps(f, other, 0.0)) << object.name << " in session " << s;
        }
        placed.push_back(f);
      }
    }
  }
}

TEST(World, ChangeLabelsMatchPoses) {
  const World world = World::load(findWorld("warehouse"));
  for (int s = 1; s < world.sessionCount(); ++s) {
    for (const ObjectState& now : world.session(s).objects) {
      const ObjectState& before = world.session(s - 1).objects[now.id - 1];
      Change expected = Change::kNone;
      if (before.present && !now.present) expected = Change::kRemoved;
      if (!before.present && now.present) expected = Change::kAdded;
      if (before.present && now.present && !before.T_W_O.isApprox(now.T_W_O)) {
        expected = Change::kMoved;
      }
      EXPECT_EQ(now.since_previous, expected) << now.name << " in session " << s;
    }
  }
}

TEST(World, DoorsOpenTheWalls) {
  const World world = World::load(findWorld("office"));
  const auto scene = world.buildScene(0);
  // Through the office_a door (x = 3, y = 3.95) from office_a into the corridor, at 1 m height.
  std::vector<RayHit> hits;
  scene->intersect({{Eigen::Vector3f(3.0f, 3.0f, 1.0f), Eigen::Vector3f::UnitY()}}, hits);
  EXPECT_GT(hits[0].t_m, 2.0f);  // passes the wall at y = 3.9 .. 4.0
  // Beside the door the wall is there.
  scene->intersect({{Eigen::Vector3f(2.0f, 3.0f, 1.0f), Eigen::Vector3f::UnitY()}}, hits);
  EXPECT_NEAR(hits[0].t_m, 0.9f, 1e-5f);
  // Above the door, the lintel.
  scene->intersect({{Eigen::Vector3f(3.0f, 3.0f, 2.3f), Eigen::Vector3f::UnitY()}}, hits);
  EXPECT_NEAR(hits[0].t_m, 0.9f, 1e-5f);
}

TEST(World, ObjMeshObjectsAndOptionalFiles) {
  const fs::path dir = strata::test::freshTempDir("world_obj");
  std::ofstream((dir / "cube.obj").string())
      << "# unit cube, quads, one face with negative indices\n"
         "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
         "f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 3 4 8 7\nf 2/1 3/1 7/1 6/1\nf -8//1 -4//1 -1//1 "
         "-5//1\n";
  const Mesh cube = readObj((dir / "cube.obj").string());
  EXPECT_EQ(cube.triangles.size(), 12u);
  EXPECT_TRUE(analyzeTopology(cube).isClosedOriented());

  const std::string rooms = "rooms: [{min: [0, 0], max: [4, 3], height: 2.5}]\nsessions: 1\n";
  const World world = World::fromYaml(
      rooms +
          "objects:\n  - {name: cube, type: mesh, file: cube.obj, scale: 0.5, at: [2, 1.5]}\n"
          "  - {name: ghost, type: mesh, file: missing.obj, optional: true}\n",
      "mesh.yaml", World::Options{}, dir.string());
  ASSERT_EQ(world.objectCount(), 1);  // the optional missing mesh is skipped
  EXPECT_TRUE(world.object(1).shape.size_m.isApprox(Eigen::Vector3d::Constant(0.5)));
  const auto scene = world.buildScene(0);
  EXPECT_NEAR(scene->signedDistance({2.0f, 1.5f, 0.3f}), -0.2f, 1e-5f);
  EXPECT_NEAR(scene->signedDistance({2.0f, 1.5f, 0.7f}), 0.2f, 1e-5f);

  const std::string message = [&] {
    try {
      World::fromYaml(rooms + "objects:\n  - {name: gone, type: mesh, file: missing.obj}\n",
                      "mesh.yaml", World::Options{}, dir.string());
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  }();
  EXPECT_NE(message.find("mesh.yaml:4: objects[0].file: mesh file"), std::string::npos) << message;
  fs::remove_all(dir);
}

TEST(World, BunnyMeshObject) {
  STRATA_REQUIRE_DATA("meshes/stanford-bunny.obj", bunny_path);
  const World world = World::fromYaml(
      "rooms: [{min: [0, 0], max: [4, 3], height: 2.5}]\nsessions: 1\nobjects:\n"
      "  - {name: bunny, type: mesh, file: '" +
          bunny_path + "', up: y, scale: 2, at: [2, 1.5]}\n",
      "bunny.yaml");
  EXPECT_NEAR(world.object(1).shape.size_m.z(), 2 * 0.1543, 0.01);  // y extent of the file
  const auto scene = world.buildScene(0);
  std::vector<RayHit> hits;
  scene->intersect({{Eigen::Vector3f(2.0f, 1.5f, 1.0f), -Eigen::Vector3f::UnitZ()}}, hits);
  EXPECT_EQ(hits[0].object_id, 1);
  EXPECT_GT(scene->signedDistance({2.0f, 1.5f, 1.0f}), 0.5f);
}

TEST(World, LightingVariesPerSessionWhenAsked) {
  const World room = World::load(defaultWorldPath());
  const Light& first = room.session(0).light;
  EXPECT_TRUE(first.direction_W.isApprox(Eigen::Vector3d(0.3, -0.4, 1.0).normalized()));
  EXPECT_DOUBLE_EQ(first.intensity, 0.65);
  const Light& later = room.session(1).light;
  const double angle = std::acos(std::clamp(later.direction_W.dot(first.direction_W), -1.0, 1.0));
  EXPECT_LE(angle, 15.0 * M_PI / 180.0 + 1e-9);
  EXPECT_NE(later.intensity, first.intensity);
  EXPECT_NEAR(later.intensity, 0.65, 0.65 * 0.2 + 1e-12);
}

TEST(World, WorldsDirOverride) {
  const fs::path dir = strata::test::freshTempDir("world_worlds_dir");
  fs::copy_file(defaultWorldPath(), dir / "room.yaml");
  setenv("STRATA_WORLDS_DIR", dir.c_str(), 1);
  EXPECT_EQ(defaultWorldPath(), (dir / "room.yaml").string());
  EXPECT_EQ(findWorld("room"), (dir / "room.yaml").string());
  unsetenv("STRATA_WORLDS_DIR");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::sim

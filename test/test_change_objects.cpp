// Object discovery on constructed inputs (change_test_scene.h: a floor with two boxes, a flat
// poster, a pebble and a mislabelled floor patch) and the mesh segmentation steps.
#include <gtest/gtest.h>

#include <algorithm>

#include "strata/change/change_detector.h"
#include "strata/change/object_discovery.h"
#include "strata/change/region_growing.h"
#include "change_test_scene.h"
#include "strata/core/error.h"

namespace strata::change {
namespace {

using test::kBoxA;
using test::kBoxB;
using test::kVoxel;
using test::makeObjectsScene;

TEST(ChangeObjects, FindsBoxesDropsPlanarAndSmallPieces) {
  const test::ObjectsScene scene = makeObjectsScene();
  ObjectStats stats;
  const std::vector<DiscoveredObject> objects =
      extractObjects(scene.map, scene.labels, ObjectConfig{}, 3, &stats);
  ASSERT_EQ(objects.size(), 2u) << "components " << stats.components << ", planar "
                                << stats.dropped_planar << ", small " << stats.dropped_small;
  EXPECT_GE(stats.dropped_planar, 1u);                                   // the poster
  EXPECT_GE(stats.dropped_small, 1u);                                    // the pebble
  EXPECT_LT(stats.dynamic_faces_refined, stats.dynamic_faces_labelled);  // floor fringe undone
  const Eigen::AlignedBox3d* expected[] = {&kBoxA, &kBoxB};              // largest first
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const DiscoveredObject& o = objects[i];
    EXPECT_EQ(o.id, static_cast<int>(i) + 1);
    EXPECT_EQ(o.session, 3);
    EXPECT_EQ(o.vertex_count, o.mesh.vertices.size());
    EXPECT_EQ(o.mesh.normals.size(), o.mesh.vertices.size());
    const Eigen::AlignedBox3f truth = expected[i]->cast<float>();
    // The top and sides of the box, at most a voxel or two of floor fringe around its foot.
    EXPECT_NEAR(o.bbox.max().z(), truth.max().z(), kVoxel);
    EXPECT_LT(o.bbox.min().z(), kVoxel);
    for (int k = 0; k < 2; ++k) {
      EXPECT_NEAR(o.bbox.min()[k], truth.min()[k], 2.5f * kVoxel) << "object " << o.id;
      EXPECT_NEAR(o.bbox.max()[k], truth.max()[k], 2.5f * kVoxel) << "object " << o.id;
    }
    EXPECT_NEAR(o.centroid.x(), truth.center().x(), 0.05f);
    EXPECT_NEAR(o.centroid.y(), truth.center().y(), 0.05f);
  }
}

TEST(ChangeObjects, NothingDynamicGivesNoObjects) {
  test::ObjectsScene scene = makeObjectsScene();
  const LabelMap none = test::makeLabels(scene.map, [](const Eigen::Vector3d&) { return false; });
  EXPECT_TRUE(extractObjects(scene.map, none, ObjectConfig{}).empty());
  LabelMap empty;
  empty.voxel_size_m = kVoxel;
  EXPECT_TRUE(extractObjects(scene.map, empty, ObjectConfig{}).empty());
}

TEST(ChangeObjects, IsDeterministic) {
  const test::ObjectsScene scene = makeObjectsScene();
  const auto a = extractObjects(scene.map, scene.labels, ObjectConfig{});
  const auto b = extractObjects(scene.map, scene.labels, ObjectConfig{});
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].mesh.vertices, b[i].mesh.vertices);
    EXPECT_EQ(a[i].mesh.triangles, b[i].mesh.triangles);
  }
}

TEST(ChangeObjects, ConfigIsValidated) {
  const test::ObjectsScene scene = makeObjectsScene();
  ObjectConfig bad;
  bad.region_dynamic_share = 1.5f;
  EXPECT_THROW(extractObjects(scene.map, scene.labels, bad), InputError);
  bad = ObjectConfig{};
  bad.min_vertices = 0;
  EXPECT_THROW(bad.validate(), InputError);
  LabelMap coarse = scene.labels;
  coarse.voxel_size_m = 0.05f;
  EXPECT_THROW(extractObjects(scene.map, coarse, ObjectConfig{}), InputError);
}

/// A 2 x 2 m floor with one box on it, free space observed (as with free-space allocation).
TsdfMap floorWithBox(const Eigen::AlignedBox3d& box) {
  return test::makeSdfMap(
      [&](const Eigen::Vector3d& p) { return std::min(p.z(), test::boxSdf(p, box)); }, {0, 0, -0.1},
      {2, 2, 1.1}, kVoxel, [](const Eigen::Vector3d&) { return true; });
}

TEST(ChangeObjects, SessionObjectsThroughTheReferenceDetector) {
  // The box stands at A in session 0 and at B in session 1: S ends with the bare floor, and each
  // session's box is its only object.
  ChangeDetector detector(floorWithBox(kBoxA).config(), ChangeConfig{});
  detector.endSession(detector.addSessionMap(floorWithBox(kBoxA)));
  detector.endSession(detector.addSessionMap(floorWithBox(kBoxB)));
  for (int session = 0; session < 2; ++session) {
    const auto objects = sessionObjects(detector, session);
    ASSERT_EQ(objects.size(), 1u) << "session " << session;
    const Eigen::Vector3d centre = (session == 0 ? kBoxA : kBoxB).center();
    EXPECT_NEAR(objects[0].centroid.x(), centre.x(), 0.05) << "session " << session;
    EXPECT_NEAR(objects[0].centroid.y(), centre.y(), 0.05) << "session " << session;
    EXPECT_EQ(objects[0].session, session);
  }
}

TEST(RegionGrowing, SplitsACubeIntoItsSixFaces) {
  Mesh cube = test::boxMesh(Eigen::AlignedBox3d(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones()));
  const FaceAdjacency adjacency = buildFaceAdjacency(cube);
  for (std::size_t f = 0; f < cube.triangles.size(); ++f) {
    EXPECT_EQ(adjacency.offsets[f + 1] - adjacency.offsets[f], 3u);
  }
  const Regions regions = growSmoothRegions(cube, adjacency, 25.0f, 40.0f);
  EXPECT_EQ(regions.count, 6u);
  // One dynamic triangle of two is 50 % > 25 %: its whole face turns dynamic.
  std::vector<bool> dynamic(cube.triangles.size(), false);
  dynamic[0] = true;
  const std::vector<bool> refined = labelRegions(regions, dynamic, 0.25f);
  EXPECT_TRUE(refined[0] && refined[1]);
  EXPECT_EQ(std::count(refined.begin(), refined.end(), true), 2);
  EXPECT_EQ(connectedComponents(adjacency, refined).count, 1u);
  EXPECT_EQ(connectedComponents(adjacency, std::vector<bool>(12, true)).count, 1u);
}

TEST(RegionGrowing, JoinsComponentsAcrossSmallGaps) {
  // Two unit-ish cubes 3 cm apart (a leg cut off from its seat) and a third far away.
  Mesh mesh =
      test::boxMesh(Eigen::AlignedBox3d(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.2, 0.2, 0.2)));
  for (const double x0 : {0.23, 1.0}) {
    const Mesh other = test::boxMesh(
        Eigen::AlignedBox3d(Eigen::Vector3d(x0, 0, 0), Eigen::Vector3d(x0 + 0.2, 0.2, 0.2)));
    const int offset = static_cast<int>(mesh.vertices.size());
    mesh.vertices.insert(mesh.vertices.end(), other.vertices.begin(), other.vertices.end());
    for (const auto& t : other.triangles)
      mesh.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  }
  const Components strict =
      connectedComponents(buildFaceAdjacency(mesh), std::vector<bool>(mesh.triangles.size(), true));
  ASSERT_EQ(strict.count, 3u);
  EXPECT_EQ(mergeNearbyComponents(mesh, strict, 0.02f).count, 3u);
  const Components joined = mergeNearbyComponents(mesh, strict, 0.04f);
  EXPECT_EQ(joined.count, 2u);
  EXPECT_EQ(joined.component[0], joined.component[12]);  // first two cubes: one object
  EXPECT_NE(joined.component[0], joined.component[24]);
  EXPECT_EQ(mergeNearbyComponents(mesh, strict, 0.0f).count, 3u);
}

}  // namespace
}  // namespace strata::change

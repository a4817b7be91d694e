// Evaluation of change detection on constructed cases: found / over- / under-segmented / false
// positive segments, the static map's completeness and ghosts, visibility from rendered frames.
#include <gtest/gtest.h>

#include "strata/change/eval/evaluation.h"
#include "strata/change/eval/evaluation_truth.h"
#include "strata/change/eval/evaluation_visibility.h"
#include "strata/change/eval/evaluation_world.h"
#include "change_test_scene.h"
#include "strata/core/error.h"
#include "strata/sim/world/world_paths.h"

namespace strata::change {
namespace {

using Box = Eigen::AlignedBox3d;

/// Points every 1 cm on the top and sides of a box (what a camera walking around it sees).
std::vector<Eigen::Vector3f> seenPoints(const Box& box) {
  std::vector<Eigen::Vector3f> points;
  const Eigen::Vector3d lo = box.min(), hi = box.max();
  for (double a = lo.x(); a <= hi.x(); a += 0.01) {
    for (double b = lo.y(); b <= hi.y(); b += 0.01) points.emplace_back(a, b, hi.z());
  }
  for (double z = lo.z(); z <= hi.z(); z += 0.01) {
    for (double a = lo.x(); a <= hi.x(); a += 0.01) {
      points.emplace_back(a, lo.y(), z);
      points.emplace_back(a, hi.y(), z);
    }
    for (double b = lo.y(); b <= hi.y(); b += 0.01) {
      points.emplace_back(lo.x(), b, z);
      points.emplace_back(hi.x(), b, z);
    }
  }
  return points;
}

TruthObject truthBox(int id, const Box& box, bool moved) {
  TruthObject object{id, "box" + std::to_string(id), moved, test::boxMesh(box), seenPoints(box)};
  object.visible_area_m2 = static_cast<float>(object.visible_points.size()) * 1e-4f;
  return object;
}

/// A segment made of some faces of a mesh (all when `faces` is empty).
DiscoveredObject segment(int id, const Mesh& mesh, std::vector<int> faces = {}) {
  DiscoveredObject s;
  s.id = id;
  s.mesh.vertices = mesh.vertices;
  if (faces.empty()) s.mesh.triangles = mesh.triangles;
  for (const int f : faces) s.mesh.triangles.push_back(mesh.triangles[static_cast<std::size_t>(f)]);
  for (const Eigen::Vector3f& v : s.mesh.vertices) s.bbox.extend(v);
  s.vertex_count = s.mesh.vertices.size();
  return s;
}

Mesh merged(const Mesh& a, const Mesh& b) {
  Mesh out = a;
  const int offset = static_cast<int>(a.vertices.size());
  out.vertices.insert(out.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const Eigen::Vector3i& t : b.triangles)
    out.triangles.push_back(t + Eigen::Vector3i::Constant(offset));
  return out;
}

const Box kA(Eigen::Vector3d(0.5, 0.5, 0), Eigen::Vector3d(0.9, 0.8, 0.4));
const Box kB(Eigen::Vector3d(2.0, 0.5, 0), Eigen::Vector3d(2.6, 1.1, 0.6));
const Box kC(Eigen::Vector3d(1.0, 2.0, 0), Eigen::Vector3d(1.3, 2.3, 0.3));
const Box kFloorPatch(Eigen::Vector3d(3, 3, 0), Eigen::Vector3d(3.5, 3.5, 0.01));

TEST(ChangeEvaluation, FoundOverSegmentedAndFalsePositive) {
  const std::vector<TruthObject> truth = {truthBox(1, kA, true), truthBox(2, kB, true),
                                          truthBox(3, kC, false)};
  const Mesh b = test::boxMesh(kB);
  // test::boxMesh faces: 0-3 the x sides, 4-7 the y sides, 10-11 the top. Box B in three pieces,
  // none covering half of it.
  const std::vector<DiscoveredObject> segments = {
      segment(1, test::boxMesh(kA)), segment(2, b, {10, 11}), segment(3, b, {0, 1, 2, 3}),
      segment(4, b, {4, 5, 6, 7}), segment(5, test::boxMesh(kFloorPatch))};
  const SessionObjectEvaluation e = evaluateObjects(2, truth, segments, EvaluationConfig{});
  ASSERT_EQ(e.objects.size(), 2u);  // the moved ones
  EXPECT_TRUE(e.objects[0].found);
  EXPECT_EQ(e.objects[0].best_segment, 1);
  EXPECT_NEAR(e.objects[0].coverage, 1.0, 1e-9);
  EXPECT_FALSE(e.objects[1].found) << "coverage " << e.objects[1].coverage;
  EXPECT_EQ(e.objects[1].segments, 3);
  EXPECT_EQ(e.segments[4].object_id, 0);
  EXPECT_EQ(e.counts.moved, 2u);
  EXPECT_EQ(e.counts.found, 1u);
  EXPECT_EQ(e.counts.segments, 5u);
  EXPECT_EQ(e.counts.false_positives, 1u);
  EXPECT_EQ(e.counts.over_segmented, 1u);
  EXPECT_EQ(e.counts.under_segmented, 0u);
  EXPECT_DOUBLE_EQ(e.counts.precision(), 0.8);
  EXPECT_DOUBLE_EQ(e.counts.recall(), 0.5);
}

TEST(ChangeEvaluation, UnderSegmentedSegmentFindsNeither) {
  const Box d(Eigen::Vector3d(1.0, 1.4, 0), Eigen::Vector3d(1.5, 1.9, 0.5));  // beside kC
  const std::vector<TruthObject> truth = {truthBox(1, d, true), truthBox(3, kC, false)};
  const std::vector<DiscoveredObject> segments = {
      segment(1, merged(test::boxMesh(d), test::boxMesh(kC)))};
  const SessionObjectEvaluation e = evaluateObjects(1, truth, segments, EvaluationConfig{});
  EXPECT_EQ(e.segments[0].object_id, 1);  // mostly on the moved box: not a false positive
  EXPECT_TRUE(e.segments[0].under_segmented);
  EXPECT_FALSE(e.objects[0].found);  // only ~74 % of the segment lies on it
  EXPECT_EQ(e.counts.under_segmented, 1u);
  EXPECT_DOUBLE_EQ(e.counts.precision(), 1.0);
  EXPECT_DOUBLE_EQ(e.counts.recall(), 0.0);
}

TEST(ChangeEvaluation, BarelySeenObjectsAreNotCounted) {
  TruthObject glimpsed = truthBox(1, kA, true);
  glimpsed.visible_points.resize(20);
  glimpsed.visible_area_m2 = 0.002f;
  const SessionObjectEvaluation e = evaluateObjects(1, {glimpsed}, {}, EvaluationConfig{});
  ASSERT_EQ(e.objects.size(), 1u);
  EXPECT_FALSE(e.objects[0].evaluated);
  EXPECT_EQ(e.counts.moved, 0u);
  EXPECT_DOUBLE_EQ(e.counts.recall(), 1.0);
  EvaluationConfig bad;
  bad.found_min_coverage = 2.0f;
  EXPECT_THROW(evaluateObjects(1, {}, {}, bad), InputError);
}

TEST(ChangeEvaluation, StaticMapCompletenessAndGhosts) {
  const Box floor(Eigen::Vector3d(0, 0, -0.1), Eigen::Vector3d(4, 4, 0));
  const Mesh floor_mesh = test::boxMesh(floor);
  // Reconstructed: the floor, the unchanged box C, and a ghost of box A where it no longer is.
  const Mesh static_mesh = merged(merged(floor_mesh, test::boxMesh(kC)), test::boxMesh(kA));
  const Mesh static_truth = merged(floor_mesh, test::boxMesh(kC));
  std::vector<Eigen::Vector3f> seen = seenPoints(kC);
  const std::size_t on_c = seen.size();
  for (int i = 0; i < 100; ++i) seen.emplace_back(0.1f + 0.03f * i, 3.5f, 0.0f);  // floor
  for (int i = 0; i < 100; ++i)
    seen.emplace_back(0.1f + 0.03f * i, 3.5f, 0.5f + 0.01f * (i % 2));  // missing
  const StaticMapEvaluation e =
      evaluateStaticMap(static_mesh, static_truth, {test::boxMesh(kA)}, seen, EvaluationConfig{});
  EXPECT_EQ(e.seen_points, on_c + 200);
  EXPECT_NEAR(e.completeness, double(on_c + 100) / double(on_c + 200), 1e-9);
  // Box A's faces other than its bottom (which lies on the floor) are ghosts.
  const Eigen::Vector3d s = kA.sizes();
  const double ghost = s.x() * s.y() + 2 * s.z() * (s.x() + s.y());
  EXPECT_NEAR(e.ghost_area_m2, ghost, 1e-4);
  EXPECT_GT(e.ghostShare(), 0.0);
  EXPECT_LT(e.ghostShare(), 0.05);
}

TEST(ChangeEvaluation, VisibleSurfaceBackProjectsExactDepthByObject) {
  CameraIntrinsics k;
  k.width_px = 64;
  k.height_px = 48;
  k.cx_px = 31.5f;
  k.cy_px = 23.5f;
  sim::SimulatedFrame frame;
  frame.depth = DepthImage(64, 48, 1.5f);
  frame.depth_true = DepthImage(64, 48, 1.5f);
  frame.object_ids = sim::ObjectIdImage(64, 48);
  for (int v = 0; v < 48; ++v) {
    for (int u = 0; u < 64; ++u)
      frame.object_ids.ids[static_cast<std::size_t>(v * 64 + u)] = u < 32 ? 4 : 0;
  }
  frame.depth.at(0, 0) = 0.0f;  // dropped out: not seen
  VisibleSurface seen(0.001f, 1);
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  T_W_C.translation() = Eigen::Vector3d(1, 2, 3);
  seen.addFrame(frame, k, T_W_C);
  EXPECT_EQ(seen.objectIds(), (std::vector<int>{0, 4}));
  EXPECT_EQ(seen.points(4).size(), 32u * 48u - 1u);
  for (const Eigen::Vector3f& p : seen.points(4)) {
    EXPECT_LT(p.x(), 1.0f);
    EXPECT_NEAR(p.z(), 4.5f, 1e-5f);
  }
  seen.addFrame(frame, k, T_W_C);  // the same view again: no new points, a second view of each
  EXPECT_EQ(seen.points(0).size(), 32u * 48u);
  EXPECT_EQ(seen.points(0, 2).size(), 32u * 48u);
  EXPECT_TRUE(seen.points(0, 3).empty());
}

TEST(ChangeEvaluation, MovedObjectsOfTheShippedRoom) {
  const sim::World world = sim::World::load(sim::defaultWorldPath());
  const std::vector<int> changing = changingObjectIds(world);
  EXPECT_FALSE(changing.empty());
  for (int s = 1; s < world.sessionCount(); ++s) {
    const std::vector<int> earlier = movedObjectIds(world, s, MovedReference::kEarlierSessions);
    const std::vector<int> all = movedObjectIds(world, s, MovedReference::kAllSessions);
    for (const sim::ObjectState& o : world.session(s).objects) {
      const bool changed_now =
          o.since_previous == sim::Change::kMoved || o.since_previous == sim::Change::kAdded;
      const auto has = [&](const std::vector<int>& ids) {
        return std::find(ids.begin(), ids.end(), o.id) != ids.end();
      };
      if (changed_now) {
        EXPECT_TRUE(has(earlier) && has(all)) << "session " << s << " object " << o.id;
      }
      if (has(all)) {
        EXPECT_TRUE(o.present && has(changing));
      }
    }
  }
}

// Arrivals: a moved object counts only in the sessions in which it changed since the one before.
TEST(ChangeEvaluation, ArrivalsCountOnlyTheSessionsInWhichAnObjectChanged) {
  const sim::World world = sim::World::load(sim::defaultWorldPath());
  ASSERT_GE(world.sessionCount(), 2);
  const std::vector<int> changed = world.session(1).changedIds();
  ASSERT_FALSE(changed.empty());
  int unchanged = 0;  // an object that stood in session 1 as in session 0
  for (const sim::ObjectState& o : world.session(1).objects) {
    if (o.present && o.since_previous == sim::Change::kNone) unchanged = o.id;
  }
  ASSERT_NE(unchanged, 0);
  const auto match = [](int id, bool evaluated, bool found) {
    ObjectMatch m;
    m.object_id = id;
    m.evaluated = evaluated;
    m.found = found;
    return m;
  };
  WorldEvaluation evaluation;
  evaluation.sessions.resize(2);
  evaluation.sessions[0].session = 0;  // session 0 has no arrivals, whatever it shows
  evaluation.sessions[0].objects = {match(changed[0], true, true)};
  evaluation.sessions[1].session = 1;
  evaluation.sessions[1].objects = {match(changed[0], true, false), match(unchanged, true, true)};
  ArrivalCounts counts = arrivalCounts(world, evaluation);
  EXPECT_EQ(counts.arrivals, 1u);  // the changed object; the unchanged instance is left out
  EXPECT_EQ(counts.found, 0u);
  evaluation.sessions[1].objects[0].found = true;
  counts = arrivalCounts(world, evaluation);
  EXPECT_EQ(counts.found, 1u);
  EXPECT_DOUBLE_EQ(counts.recall(), 1.0);
  evaluation.sessions[1].objects[0].evaluated = false;  // too little of it seen: not counted
  EXPECT_EQ(arrivalCounts(world, evaluation).arrivals, 0u);
  evaluation.sessions.resize(world.sessionCount() + 1);
  EXPECT_THROW(arrivalCounts(world, evaluation), InputError);
}

}  // namespace
}  // namespace strata::change

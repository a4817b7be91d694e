// Carrying observations forward into a session's change-detection layer (change/carry_forward.h)
// around the points keyframes confirmed (select/confirmed_points.h, tested with the other
// selection-side helpers in test_changed_views.cpp): the per-voxel rule, the latest-observation
// map, bad input, and the reference detector finding an object that stands as before in a
// session that fused none of its frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "strata/change/carry_forward.h"
#include "strata/change/change_detector.h"
#include "strata/change/object_discovery.h"
#include "change_test_scene.h"
#include "strata/core/error.h"

namespace strata::change {
namespace {

using test::kBoxA;
using test::kVoxel;

MapConfig gridConfig(float voxel_m = kVoxel) {
  MapConfig c;
  c.voxel_size_m = voxel_m;
  return c;
}

void setVoxel(TsdfMap& map, const GlobalVoxelIndex& v, float tsdf_m, float weight) {
  map.allocateVoxel(v) = TsdfVoxel{tsdf_m, weight, 7u};
}

float weightAt(const TsdfMap& map, const GlobalVoxelIndex& v) {
  const TsdfVoxel* voxel = map.findVoxel(v);
  return voxel == nullptr ? -1.0f : voxel->weight;
}

TEST(CarryForward, FillsOnlyUnobservedVoxelsWithinTheRadiusFromObservedOnes) {
  TsdfMap latest(gridConfig()), session(gridConfig());
  for (int x = -5; x <= 5; ++x) setVoxel(latest, {x, 0, 0}, 0.01f * x, 5.0f);
  setVoxel(latest, {1, 0, 0}, 0.5f, 2.0f);     // seen in too few frames: not observed
  setVoxel(session, {-1, 0, 0}, -0.3f, 4.0f);  // the session observed it itself
  setVoxel(session, {0, 0, 0}, 0.2f, 1.0f);    // seen, but not observed
  // Centre of voxel (0,0,0), radius 2.5 voxels: x in [-2, 2] on the row.
  const ConfirmedPoint point{Eigen::Vector3f(0.5f, 0.5f, 0.5f) * kVoxel, 2.5f * kVoxel};
  const CarryStats stats = carryObserved(latest, {point}, 3.0f, session);
  EXPECT_EQ(stats.points, 1u);
  EXPECT_EQ(stats.voxels, 3u);  // x = -2, 0, 2: -1 is the session's, 1 is unobserved in latest
  EXPECT_FLOAT_EQ(session.findVoxel({-2, 0, 0})->tsdf_m, -0.02f);
  EXPECT_FLOAT_EQ(session.findVoxel({0, 0, 0})->weight, 5.0f);
  EXPECT_EQ(session.findVoxel({2, 0, 0})->color_rgba, 7u);
  EXPECT_FLOAT_EQ(session.findVoxel({-1, 0, 0})->tsdf_m, -0.3f);  // kept
  EXPECT_FLOAT_EQ(weightAt(session, {1, 0, 0}), 0.0f);            // allocated, left unobserved
  EXPECT_FLOAT_EQ(weightAt(session, {3, 0, 0}), 0.0f);            // outside the ball
  // A point with a bad position or radius carries nothing.
  const ConfirmedPoint nan{Eigen::Vector3f(NAN, 0.0f, 0.0f), 0.1f};
  const ConfirmedPoint negative{Eigen::Vector3f::Zero(), -1.0f};
  TsdfMap empty(gridConfig());
  EXPECT_EQ(carryObserved(latest, {nan, negative}, 3.0f, empty).voxels, 0u);
  EXPECT_EQ(empty.blockCount(), 0u);
}

TEST(CarryForward, LatestHoldsTheLastObservationOfEveryVoxel) {
  TsdfMap latest(gridConfig()), first(gridConfig()), second(gridConfig());
  setVoxel(first, {0, 0, 0}, 0.01f, 4.0f);
  setVoxel(first, {20, 0, 0}, 0.02f, 4.0f);
  setVoxel(second, {0, 0, 0}, -0.03f, 6.0f);
  setVoxel(second, {20, 0, 0}, 0.9f, 1.0f);  // not observed: keeps the first session's value
  setVoxel(second, {40, 0, 0}, 0.9f, 1.0f);  // not observed anywhere: no block in latest
  keepLatestObserved(first, 3.0f, latest);
  keepLatestObserved(second, 3.0f, latest);
  EXPECT_FLOAT_EQ(latest.findVoxel({0, 0, 0})->tsdf_m, -0.03f);
  EXPECT_FLOAT_EQ(latest.findVoxel({20, 0, 0})->tsdf_m, 0.02f);
  EXPECT_EQ(latest.findVoxel({40, 0, 0}), nullptr);
}

TEST(CarryForward, RejectsMapsOfAnotherVoxelSize) {
  TsdfMap latest(gridConfig(0.04f)), session(gridConfig());
  EXPECT_THROW(carryObserved(latest, {}, 3.0f, session), InputError);
  EXPECT_THROW(keepLatestObserved(session, 3.0f, latest), InputError);
}

/// A floor over 2 x 2 m, with box A on it or not; observed where `observed` holds.
TsdfMap floorMap(bool with_box, const test::PointTest& observed) {
  return test::makeSdfMap(
      [&](const Eigen::Vector3d& p) {
        return with_box ? std::min(p.z(), test::boxSdf(p, kBoxA)) : p.z();
      },
      {0, 0, -0.1}, {2, 2, 1.1}, kVoxel, observed);
}

/// Points on box A's top and sides every 4 cm, as a keyframe's samples would confirm them.
std::vector<ConfirmedPoint> boxSurfacePoints() {
  std::vector<ConfirmedPoint> points;
  const Eigen::Vector3d lo = kBoxA.min(), hi = kBoxA.max();
  for (double x = lo.x(); x <= hi.x() + 1e-9; x += 0.04) {
    for (double y = lo.y(); y <= hi.y() + 1e-9; y += 0.04) {
      points.push_back({Eigen::Vector3d(x, y, hi.z()).cast<float>(), 0.04f});
    }
    for (double z = 0.0; z <= hi.z() + 1e-9; z += 0.04) {
      points.push_back({Eigen::Vector3d(x, lo.y(), z).cast<float>(), 0.04f});
      points.push_back({Eigen::Vector3d(x, hi.y(), z).cast<float>(), 0.04f});
    }
  }
  return points;
}

TEST(CarryForward, TheDetectorFindsAnObjectStandingAsBeforeInASessionThatSkippedIt) {
  // Session 0: the bare floor. Session 1: box A arrives. Session 2: box A still stands, but the
  // session fused no frame of it (its layer is unobserved within 0.3 m of the box).
  const auto everywhere = [](const Eigen::Vector3d&) { return true; };
  const auto away_from_box = [](const Eigen::Vector3d& p) {
    return kBoxA.exteriorDistance(p) > 0.3;
  };
  for (const bool carry : {false, true}) {
    const TsdfMap first = floorMap(false, everywhere);
    const TsdfMap second = floorMap(true, everywhere);
    ChangeDetector detector(first.config(), ChangeConfig{});
    detector.endSession(detector.addSessionMap(first));
    detector.endSession(detector.addSessionMap(second));
    TsdfMap latest(first.config());
    keepLatestObserved(detector.sessionMap(0), detector.config().min_weight, latest);
    keepLatestObserved(detector.sessionMap(1), detector.config().min_weight, latest);
    const int third = detector.addSessionMap(floorMap(false, away_from_box));
    if (carry) {
      TsdfMap layer = detector.sessionMap(third);
      const CarryStats stats =
          carryObserved(latest, boxSurfacePoints(), detector.config().min_weight, layer);
      EXPECT_GT(stats.voxels, 1000u);
      detector.replaceSessionMap(third, layer);
    }
    detector.endSession(third);
    const auto objects = sessionObjects(detector, third);
    if (!carry) {
      EXPECT_TRUE(objects.empty()) << "unobserved space shows no object";
      continue;
    }
    ASSERT_EQ(objects.size(), 1u);
    EXPECT_NEAR(objects[0].centroid.x(), kBoxA.center().x(), 0.05);
    EXPECT_NEAR(objects[0].centroid.y(), kBoxA.center().y(), 0.05);
    EXPECT_NEAR(objects[0].bbox.max().z(), kBoxA.max().z(), 2 * kVoxel);
  }
}

TEST(CarryForward, ReplacingALayerNeedsAnOpenSessionOnTheSameGrid) {
  const TsdfMap floor = floorMap(false, [](const Eigen::Vector3d&) { return true; });
  ChangeDetector detector(floor.config(), ChangeConfig{});
  EXPECT_THROW(detector.replaceSessionMap(0, floor), InputError);  // no such session
  const int session = detector.addSessionMap(floor);
  EXPECT_THROW(detector.replaceSessionMap(session, TsdfMap(gridConfig(0.04f))), InputError);
  detector.replaceSessionMap(session, TsdfMap(floor.config()));  // emptied: allowed
  EXPECT_EQ(detector.sessionMap(session).blockCount(), 0u);
  detector.endSession(session);
  EXPECT_THROW(detector.replaceSessionMap(session, floor), InputError);  // ended
}

}  // namespace
}  // namespace strata::change

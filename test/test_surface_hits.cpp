// Depth endpoints as obstacles (explore/surface_hits.h): votes per camera place, the
// back-projection of a depth frame without its edge pixels, and the guarded collision checker on
// top of another checker.
#include <gtest/gtest.h>

#include "strata/core/error.h"
#include "strata/explore/surface_hits.h"

namespace strata::explore {
namespace {

/// Points 1 cm apart on a board 2.5 cm thick and 1 m wide at x in [-0.5, 0.5], y = 1 (its front
/// edge faces -y), z in [1.0, 1.025]: thinner than the voxels that would map it.
std::vector<Eigen::Vector3f> boardEdge() {
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i <= 100; ++i) {
    for (int k = 0; k <= 2; ++k) {
      points.emplace_back(-0.5f + 0.01f * static_cast<float>(i), 1.0f,
                          1.0f + 0.0125f * static_cast<float>(k));
    }
  }
  return points;
}

/// Camera positions 0.3 m apart (more than the 0.2 m baseline).
Eigen::Vector3f place(int i) { return Eigen::Vector3f(0.3f * static_cast<float>(i), -2.0f, 1.0f); }

TEST(SurfaceHits, AVoxelBlocksOnceSeenFromEnoughPlaces) {
  SurfaceHits hits;                                  // 5 cm voxels, 3 places
  const Eigen::Vector3f in_front(0.0f, 0.7f, 1.0f);  // 0.3 m in front of the edge
  for (int i = 0; i < 2; ++i) {
    hits.addPoints(boardEdge(), place(i));
    EXPECT_EQ(hits.obstacleCount(), 0u);
    EXPECT_FALSE(hits.blocks(in_front, 0.4f));
  }
  hits.addPoints(boardEdge(), place(2));
  EXPECT_GT(hits.obstacleCount(), 0u);
  EXPECT_TRUE(hits.blocks(in_front, 0.4f));
  EXPECT_FALSE(hits.blocks(in_front, 0.25f));                          // 0.3 m away
  EXPECT_FALSE(hits.blocks(Eigen::Vector3f(0.0f, 1.0f, 1.5f), 0.4f));  // 0.475 m above
  EXPECT_TRUE(hits.blocks(Eigen::Vector3f(0.9f, 1.0f, 1.0f), 0.45f));  // beyond the end
}

TEST(SurfaceHits, OnePlaceIsOneVoteHoweverOftenItSees) {
  SurfaceHits hits;
  // A camera turning in place sees the same edge ray frame after frame: its endpoints there,
  // however many, are one vote; scattered points never land in one voxel twice.
  const std::vector<Eigen::Vector3f> dense(50, Eigen::Vector3f(2.01f, 2.01f, 1.01f));
  for (int frame = 0; frame < 10; ++frame) {
    hits.addPoints(dense, place(0) + Eigen::Vector3f(0.0f, 0.01f * static_cast<float>(frame), 0));
    hits.addPoints({Eigen::Vector3f(0.1f * static_cast<float>(frame), 3.0f, 1.0f)}, place(frame));
  }
  EXPECT_EQ(hits.obstacleCount(), 0u);
  hits.addPoints(dense, place(1));
  EXPECT_EQ(hits.obstacleCount(), 0u);
  hits.addPoints(dense, place(2));  // the third place
  EXPECT_EQ(hits.obstacleCount(), 1u);
  // The obstacle is the mean of its endpoints, not the voxel centre (2.025, 2.025, 1.025).
  EXPECT_TRUE(hits.blocks(Eigen::Vector3f(2.01f, 2.01f, 1.51f), 0.5001f));
  EXPECT_FALSE(hits.blocks(Eigen::Vector3f(2.01f, 2.01f, 1.51f), 0.4999f));
}

TEST(SurfaceHits, DepthFramesBackProjectThroughTheCamera) {
  CameraIntrinsics k;
  k.width_px = 40;
  k.height_px = 30;
  k.fx_px = k.fy_px = 40.0f;
  k.cx_px = 19.5f;
  k.cy_px = 14.5f;
  DepthImage wall(40, 30, 2.0f);  // a wall 2 m ahead of the camera
  wall.at(0, 0) = std::numeric_limits<float>::quiet_NaN();
  wall.at(1, 0) = 0.0f;
  wall.at(2, 0) = 9.0f;  // beyond max_depth_m: not used
  // Camera at (1, 0, 1) looking along world +x (optical z = world x, optical x = world -y,
  // optical y = world -z).
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  T_W_C.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  T_W_C.translation() = Eigen::Vector3d(1.0, 0.0, 1.0);
  SurfaceHits hits;
  for (int i = 0; i < 3; ++i) {
    T_W_C.translation() = Eigen::Vector3d(1.0, 0.3 * i, 1.0);
    hits.addFrame(wall, k, T_W_C);
  }
  EXPECT_GT(hits.obstacleCount(), 100u);
  EXPECT_TRUE(hits.blocks(Eigen::Vector3f(2.7f, 0.3f, 1.0f), 0.35f));   // the wall is at x = 3
  EXPECT_FALSE(hits.blocks(Eigen::Vector3f(2.6f, 0.3f, 1.0f), 0.35f));  // 0.4 m from it
  EXPECT_THROW(hits.addFrame(DepthImage(20, 30, 2.0f), k, T_W_C), InputError);

  // A depth edge: beyond column 30 the far wall at 4 m, on it a flying pixel column at 3 m.
  for (int v = 0; v < 30; ++v) {
    for (int u = 31; u < 40; ++u) wall.at(u, v) = 4.0f;
    wall.at(30, v) = 3.0f;
  }
  SurfaceHitsConfig one_view;
  one_view.min_views = 1;  // every endpoint used is an obstacle at once
  SurfaceHits edge(one_view);
  T_W_C.translation() = Eigen::Vector3d(1.0, 0.0, 1.0);
  edge.addFrame(wall, k, T_W_C);
  // Column u lies at y = -(u - 19.5) * depth / 40: the flying column at (4, -0.7875), the far
  // wall from u = 32 on (u = 31 borders the edge too) at (5, <= -1.25).
  EXPECT_FALSE(edge.blocks(Eigen::Vector3f(4.0f, -0.7875f, 1.025f), 0.1f));
  EXPECT_TRUE(edge.blocks(Eigen::Vector3f(5.0f, -1.3f, 1.025f), 0.1f));
  EXPECT_TRUE(edge.blocks(Eigen::Vector3f(3.0f, -0.2f, 1.025f), 0.05f));  // the near wall
  // The near side of the edge (u = 29, y = -0.475) is the near wall's own surface: kept.
  EXPECT_TRUE(edge.blocks(Eigen::Vector3f(3.0f, -0.475f, 1.025f), 0.03f));
}

/// Every sphere is free and the ESDF reads 1 m everywhere.
class OpenSpaceChecker final : public plan::CollisionChecker {
 public:
  std::vector<std::uint8_t> spheresFree(const std::vector<Eigen::Vector3f>& centres_W, float,
                                        UnknownPolicy) override {
    return std::vector<std::uint8_t>(centres_W.size(), 1);
  }
  std::vector<EsdfSample> sample(const std::vector<Eigen::Vector3f>& points_W) override {
    EsdfSample s;
    s.distance_m = 1.0f;
    return std::vector<EsdfSample>(points_W.size(), s);
  }
  float voxelSize() const override { return 0.1f; }
  float maxDistance() const override { return 2.0f; }
};

TEST(HitGuardedChecker, RefusesWhatTheHitsBlockAndPassesTheRest) {
  SurfaceHits hits;
  for (int i = 0; i < 3; ++i) hits.addPoints(boardEdge(), place(i));
  OpenSpaceChecker open;
  HitGuardedChecker guarded(open, hits);
  const std::vector<std::uint8_t> free =
      guarded.spheresFree({Eigen::Vector3f(0.0f, 0.7f, 1.0f), Eigen::Vector3f(0.0f, 0.0f, 1.0f)},
                          0.4f, UnknownPolicy::kOccupied);
  EXPECT_EQ(free, (std::vector<std::uint8_t>{0, 1}));
  EXPECT_EQ(guarded.refusedByHits(), 1u);
  // A segment through the board's edge is refused, one beside it is not.
  EXPECT_FALSE(guarded.segmentFree(Eigen::Vector3f(-1.0f, 0.8f, 1.0f),
                                   Eigen::Vector3f(1.0f, 0.8f, 1.0f), 0.3f,
                                   UnknownPolicy::kOccupied));
  EXPECT_TRUE(guarded.segmentFree(Eigen::Vector3f(-1.0f, 0.2f, 1.0f),
                                  Eigen::Vector3f(1.0f, 0.2f, 1.0f), 0.3f,
                                  UnknownPolicy::kOccupied));
  EXPECT_FLOAT_EQ(guarded.sample({Eigen::Vector3f::Zero()})[0].distance_m, 1.0f);
  EXPECT_FLOAT_EQ(guarded.voxelSize(), 0.1f);
}

TEST(SurfaceHits, BadConfigIsAnInputError) {
  SurfaceHitsConfig c;
  c.voxel_size_m = 0.0f;
  EXPECT_THROW(SurfaceHits{c}, InputError);
  c = {};
  c.min_views = 0;
  EXPECT_THROW(SurfaceHits{c}, InputError);
  c.min_views = SurfaceHits::kMaxViews + 1;
  EXPECT_THROW(SurfaceHits{c}, InputError);
  c = {};
  c.edge_jump_m = 0.0f;
  EXPECT_THROW(SurfaceHits{c}, InputError);
  c = {};
  c.pixel_stride = 0;
  EXPECT_THROW(SurfaceHits{c}, InputError);
}

}  // namespace
}  // namespace strata::explore

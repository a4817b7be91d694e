// The topological map on the analytic room: clusters cover every traversable voxel once, portals
// join exactly the touching clusters, paths exist exactly when grid A* finds one and are about as
// long, and an incremental update after a change connects what a full rebuild connects.
#include <gtest/gtest.h>

#include <map>
#include <set>

#include "strata/plan/collision_checker.h"
#include "strata/plan/grid_astar.h"
#include "strata/plan/topo_planner.h"
#include "plan_room_scene.h"

namespace strata::plan {
namespace {

using test::PlanRoom;

constexpr float kRadiusM = 0.2f;
const TopoOptions kOptions{kRadiusM, UnknownPolicy::kOccupied};

/// Start/goal pairs over the room (voxel centres, traversable for the radius).
const std::vector<std::pair<Eigen::Vector3f, Eigen::Vector3f>> kPairs = {
    {{1.05f, 0.55f, 0.55f}, {2.95f, 0.55f, 0.55f}}, {{0.45f, 2.55f, 0.75f}, {3.55f, 0.45f, 0.45f}},
    {{3.55f, 2.65f, 0.35f}, {0.35f, 0.35f, 0.85f}}, {{0.65f, 1.45f, 0.55f}, {1.45f, 0.45f, 0.65f}},
    {{2.45f, 2.25f, 0.45f}, {3.65f, 1.15f, 0.75f}}, {{0.65f, 1.45f, 0.55f}, {2.55f, 1.05f, 0.55f}},
};

PlanRequest request(const Eigen::Vector3f& start, const Eigen::Vector3f& goal) {
  PlanRequest r;
  r.start_W = start;
  r.goal_W = goal;
  r.radius_m = kRadiusM;
  return r;
}

/// Every traversable voxel of `esdf` lies in exactly one cluster, and no other voxel in any.
void expectExactCover(const TopoMap& topo, const EsdfMap& esdf) {
  HostCollisionChecker checker(esdf);
  const TraversabilityGrid grid(checker, allocatedBounds(esdf), kRadiusM, UnknownPolicy::kOccupied);
  std::vector<int> covered(grid.cellCount(), 0);
  for (const VoxelBox& box : topo.clusters()) {
    for (int z = box.lo.z(); z <= box.hi.z(); ++z)
      for (int y = box.lo.y(); y <= box.hi.y(); ++y)
        for (int x = box.lo.x(); x <= box.hi.x(); ++x) {
          const std::int64_t i = grid.index({x, y, z});
          ASSERT_GE(i, 0);
          ++covered[static_cast<std::size_t>(i)];
        }
  }
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < covered.size(); ++i) {
    wrong += covered[i] != (grid.traversable(static_cast<std::int64_t>(i)) ? 1 : 0);
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_GT(grid.traversableCount(), 1000u);
}

/// The topological map connects two traversable voxels exactly when the grid does.
void expectSameConnectivity(const TopoMap& topo, const EsdfMap& esdf) {
  HostCollisionChecker checker(esdf);
  const TraversabilityGrid grid(checker, allocatedBounds(esdf), kRadiusM, UnknownPolicy::kOccupied);
  std::int32_t grid_count = 0, topo_count = 0;
  const std::vector<std::int32_t> grid_label = grid.components(&grid_count);
  const std::vector<std::int32_t> cluster_label = topo.components(&topo_count);
  EXPECT_EQ(grid_count, topo_count);
  std::map<std::int32_t, std::int32_t> grid_to_topo;
  std::size_t mismatched = 0;
  for (std::size_t i = 0; i < grid_label.size(); ++i) {
    if (grid_label[i] < 0) continue;
    const std::int32_t c = topo.clusterAt(grid.voxel(static_cast<std::int64_t>(i)));
    ASSERT_GE(c, 0);
    const std::int32_t t = cluster_label[static_cast<std::size_t>(c)];
    const auto [it, inserted] = grid_to_topo.emplace(grid_label[i], t);
    mismatched += it->second != t;
  }
  EXPECT_EQ(mismatched, 0u);
  std::set<std::int32_t> images;
  for (const auto& [g, t] : grid_to_topo) images.insert(t);
  EXPECT_EQ(images.size(), grid_to_topo.size());  // one to one
}

/// The blocks where two ESDFs of the same blocks differ.
std::vector<BlockIndex> changedBlocks(const EsdfMap& before, const EsdfMap& after) {
  std::vector<BlockIndex> out;
  for (const auto& [b, block] : after.blocks) {
    const EsdfBlock& old = before.blocks.at(b);
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      if (old[i].distance_m != block[i].distance_m ||
          esdfObserved(old[i]) != esdfObserved(block[i])) {
        out.push_back(b);
        break;
      }
    }
  }
  return out;
}

class TopoMapTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    open_ = new EsdfMap(PlanRoom{}.esdf());
    PlanRoom closed;
    closed.door_open = false;
    closed_ = new EsdfMap(closed.esdf());
    PlanRoom pillar;
    pillar.extra =
        Eigen::AlignedBox3d(Eigen::Vector3d(0.3, 0.3, -0.5), Eigen::Vector3d(0.6, 0.6, 2.0));
    pillar_ = new EsdfMap(pillar.esdf());
  }
  static void TearDownTestSuite() {
    delete open_;
    delete closed_;
    delete pillar_;
  }
  static EsdfMap* open_;
  static EsdfMap* closed_;
  static EsdfMap* pillar_;
};
EsdfMap* TopoMapTest::open_ = nullptr;
EsdfMap* TopoMapTest::closed_ = nullptr;
EsdfMap* TopoMapTest::pillar_ = nullptr;

TEST_F(TopoMapTest, ClustersCoverEveryTraversableVoxelOnce) {
  const TopoMap topo(*open_, kOptions);
  expectExactCover(topo, *open_);
  // Far fewer clusters than voxels: the room is mostly open.
  EXPECT_LT(topo.clusters().size() * 20, topo.stats().traversable_voxels);
}

TEST_F(TopoMapTest, PortalsJoinExactlyTheTouchingClusters) {
  const TopoMap topo(*open_, kOptions);
  ASSERT_FALSE(topo.portals().empty());
  std::set<std::pair<std::int32_t, std::int32_t>> portal_pairs;
  for (const TopoPortal& p : topo.portals()) {
    const VoxelBox& a = topo.clusters()[static_cast<std::size_t>(p.a)];
    const VoxelBox& b = topo.clusters()[static_cast<std::size_t>(p.b)];
    EXPECT_EQ(a.hi[p.axis] + 1, b.lo[p.axis]);
    EXPECT_FLOAT_EQ(p.lo_W[p.axis], static_cast<float>(b.lo[p.axis]) * PlanRoom::kVoxelM);
    for (int k = 0; k < 3; ++k) EXPECT_LE(p.lo_W[k], p.hi_W[k]);
    EXPECT_TRUE(portal_pairs.emplace(std::min(p.a, p.b), std::max(p.a, p.b)).second);
  }
  // Every 6-adjacent pair of voxels in different clusters has its portal.
  std::set<std::pair<std::int32_t, std::int32_t>> touching;
  const VoxelBox& bounds = topo.bounds();
  for (int z = bounds.lo.z(); z <= bounds.hi.z(); ++z)
    for (int y = bounds.lo.y(); y <= bounds.hi.y(); ++y)
      for (int x = bounds.lo.x(); x <= bounds.hi.x(); ++x) {
        const std::int32_t c = topo.clusterAt({x, y, z});
        if (c < 0) continue;
        for (int axis = 0; axis < 3; ++axis) {
          Eigen::Vector3i n(x, y, z);
          n[axis] += 1;
          const std::int32_t d = topo.clusterAt(n);
          if (d >= 0 && d != c) touching.emplace(std::min(c, d), std::max(c, d));
        }
      }
  EXPECT_EQ(touching, portal_pairs);
  // Each cluster lists its portals.
  for (std::size_t i = 0; i < topo.portals().size(); ++i) {
    const TopoPortal& p = topo.portals()[i];
    EXPECT_NE(std::find(topo.portalsBegin(p.a), topo.portalsEnd(p.a), static_cast<std::int32_t>(i)),
              topo.portalsEnd(p.a));
  }
  EXPECT_GT(topo.memoryBytes(), 0u);
}

TEST_F(TopoMapTest, PathExistsExactlyWhenTheGridFindsOne) {
  for (const EsdfMap* esdf : {open_, closed_}) {
    HostCollisionChecker checker(*esdf);
    GridAStarPlanner grid(*esdf, checker);
    TopoPlanner topo(*esdf, checker, kOptions);
    expectSameConnectivity(topo.map(), *esdf);
    for (const auto& [start, goal] : kPairs) {
      const PlanResult g = grid.plan(request(start, goal));
      const PlanResult t = topo.plan(request(start, goal));
      EXPECT_EQ(g.success, t.success) << g.message << " / " << t.message;
      if (!t.success) {
        EXPECT_FALSE(t.message.empty());
      }
    }
  }
}

TEST_F(TopoMapTest, PathsAboutAsLongAsTheGridsAndClear) {
  HostCollisionChecker checker(*open_);
  GridAStarPlanner grid(*open_, checker);
  TopoPlanner topo(*open_, checker, kOptions);
  const PlanRoom room;
  int compared = 0;
  for (const auto& [start, goal] : kPairs) {
    const PlanResult g = grid.plan(request(start, goal));
    const PlanResult t = topo.plan(request(start, goal));
    ASSERT_TRUE(g.success) << g.message;
    ASSERT_TRUE(t.success) << t.message;
    ++compared;
    EXPECT_EQ(t.path_W.front(), start);
    EXPECT_EQ(t.path_W.back(), goal);
    EXPECT_LT(t.length_m, 1.15 * g.length_m) << "pair " << compared;
    EXPECT_GT(t.length_m, (goal - start).norm() - 1e-4);
    // The legs stay over traversable voxel centres: clear of the surfaces by the radius, less at
    // most half a voxel between centres.
    double clearance = 1e9;
    for (std::size_t i = 1; i < t.path_W.size(); ++i) {
      for (int k = 0; k <= 200; ++k) {
        const Eigen::Vector3f p = t.path_W[i - 1] + (t.path_W[i] - t.path_W[i - 1]) * (k / 200.0f);
        clearance = std::min(clearance, room.signedDistance(p.cast<double>()));
      }
    }
    EXPECT_GT(clearance, kRadiusM - 0.5 * PlanRoom::kVoxelM);
  }
}

TEST_F(TopoMapTest, RefusesEndpointsInCollisionOrOutside) {
  HostCollisionChecker checker(*open_);
  TopoPlanner topo(*open_, checker, kOptions);
  const PlanResult wall = topo.plan(request({2.05f, 0.55f, 0.55f}, {2.95f, 0.55f, 0.55f}));
  EXPECT_FALSE(wall.success);
  EXPECT_NE(wall.message.find("in collision"), std::string::npos) << wall.message;
  const PlanResult outside = topo.plan(request({1.05f, 0.55f, 0.55f}, {9.0f, 0.5f, 0.5f}));
  EXPECT_FALSE(outside.success);
  EXPECT_NE(outside.message.find("outside the map"), std::string::npos) << outside.message;
}

TEST_F(TopoMapTest, IncrementalUpdateConnectsLikeAFullRebuild) {
  // A pillar in a corner: a local change, so most clusters stay.
  TopoMap topo(*open_, kOptions);
  const std::size_t before = topo.clusters().size();
  const std::vector<BlockIndex> changed = changedBlocks(*open_, *pillar_);
  ASSERT_FALSE(changed.empty());
  topo.update(*pillar_, changed);
  EXPECT_FALSE(topo.stats().last_update_full);
  EXPECT_GT(topo.stats().clusters_dropped, 0u);
  EXPECT_LE(topo.stats().clusters_dropped, before);
  // Only the blocks within reach of the change were tested again.
  EXPECT_LT(topo.stats().voxels_retested, topo.stats().grid_cells / 2);
  expectExactCover(topo, *pillar_);
  expectSameConnectivity(topo, *pillar_);
  // Closing the door splits the room in two: the update sees it as a rebuild does.
  const std::vector<BlockIndex> closing = changedBlocks(*pillar_, *closed_);
  TopoMap full(*closed_, kOptions);
  topo.update(*closed_, closing);
  std::int32_t updated_count = 0, full_count = 0;
  topo.components(&updated_count);
  full.components(&full_count);
  EXPECT_EQ(updated_count, full_count);
  expectExactCover(topo, *closed_);
  expectSameConnectivity(topo, *closed_);
}

TEST_F(TopoMapTest, LandmarkBoundsHoldAndKeepTheShortestRoute) {
  const TopoMap topo(*open_, kOptions);
  const TopoLandmarks& marks = topo.landmarks();
  ASSERT_GT(marks.count(), 1);
  // |d(L, p) - d(L, q)| <= d(p, q) against exact graph distances from a few portals.
  const auto n = static_cast<std::int32_t>(topo.portals().size());
  for (std::int32_t p = 0; p < n; p += std::max(1, n / 7)) {
    const std::vector<float> from_p = topo.distancesFrom(p);
    for (std::int32_t q = 0; q < n; ++q) {
      for (int l = 0; l < marks.count(); ++l) {
        EXPECT_LE(std::abs(marks.distance(l, p) - marks.distance(l, q)),
                  from_p[static_cast<std::size_t>(q)] + 1e-4f);
      }
    }
  }
  // The bounds only prune the search: the routes are as long as without landmarks.
  HostCollisionChecker checker(*open_);
  TopoPlanner with(*open_, checker, kOptions);
  TopoOptions plain = kOptions;
  plain.landmarks = 0;
  TopoPlanner without(*open_, checker, plain);
  EXPECT_EQ(without.map().landmarks().count(), 0);
  for (const auto& [start, goal] : kPairs) {
    const PlanResult a = with.plan(request(start, goal));
    const PlanResult b = without.plan(request(start, goal));
    ASSERT_TRUE(a.success && b.success);
    EXPECT_NEAR(a.length_m, b.length_m, 1e-3);
    EXPECT_LE(with.lastExpanded(), without.lastExpanded() + 0u);
  }
}

}  // namespace
}  // namespace strata::plan

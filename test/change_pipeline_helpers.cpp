#include "change_pipeline_helpers.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "strata/sim/default_scene.h"
#include "strata/sim/world/world_paths.h"

namespace strata::test {

void forEachVoxel(const TsdfMap& map, const VoxelFn& fn) {
  for (const auto& [index, block] : map.blocks()) {
    for (int z = 0; z < kBlockEdge; ++z) {
      for (int y = 0; y < kBlockEdge; ++y) {
        for (int x = 0; x < kBlockEdge; ++x) {
          fn(index * kBlockEdge + Eigen::Vector3i(x, y, z), block[linearVoxelIndex(x, y, z)]);
        }
      }
    }
  }
}

bool observedIn(const TsdfMap& map, const GlobalVoxelIndex& v, float min_weight) {
  const TsdfVoxel* voxel = map.findVoxel(v);
  return voxel != nullptr && voxel->weight >= min_weight;
}

TsdfMap observedMax(const std::vector<TsdfMap>& sessions, float min_weight) {
  TsdfMap out(sessions.front().config());
  for (const TsdfMap& session : sessions) {
    forEachVoxel(session, [&](const GlobalVoxelIndex& v, const TsdfVoxel& voxel) {
      if (voxel.weight < min_weight) return;
      TsdfVoxel& m = out.allocateVoxel(v);
      m.tsdf_m = m.weight > 0.0f ? std::max(m.tsdf_m, voxel.tsdf_m) : voxel.tsdf_m;
      m.weight = std::max(m.weight, min_weight);
    });
  }
  return out;
}

ValueComparison compareValues(const TsdfMap& actual, const TsdfMap& expected, float tolerance_m,
                              float min_weight) {
  ValueComparison c;
  forEachVoxel(expected, [&](const GlobalVoxelIndex& v, const TsdfVoxel& e) {
    const TsdfVoxel* a = actual.findVoxel(v);
    const bool a_observed = a != nullptr && a->weight >= min_weight;
    if (a_observed != (e.weight >= min_weight)) ++c.observedness_mismatches;
    if (e.weight < min_weight) return;
    ++c.compared;
    if (!a_observed || std::fabs(a->tsdf_m - e.tsdf_m) > tolerance_m) ++c.over_tolerance;
  });
  forEachVoxel(actual, [&](const GlobalVoxelIndex& v, const TsdfVoxel& a) {
    if (a.weight >= min_weight && expected.findVoxel(v) == nullptr) ++c.observedness_mismatches;
  });
  return c;
}

std::size_t dynamicNear(const change::LabelMap& labels, const sim::Box& box, float margin_m) {
  std::size_t n = 0;
  for (const auto& [index, block] : labels.blocks) {
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      if (block[i] != change::VoxelLabel::kDynamic) continue;
      const Eigen::Vector3i local(i % kBlockEdge, i / kBlockEdge % kBlockEdge, i / 64);
      const Eigen::Vector3d p =
          voxelCenter(index * kBlockEdge + local, labels.voxel_size_m).cast<double>();
      n += sim::signedDistance(box, p) <= margin_m ? 1 : 0;
    }
  }
  return n;
}

std::size_t dynamicOutside(const change::LabelMap& labels, const TsdfMap& session,
                           float min_weight) {
  std::size_t n = 0;
  for (const auto& [index, block] : labels.blocks) {
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const Eigen::Vector3i local(i % kBlockEdge, i / kBlockEdge % kBlockEdge, i / 64);
      if (block[i] == change::VoxelLabel::kDynamic &&
          !observedIn(session, index * kBlockEdge + local, min_weight)) {
        ++n;
      }
    }
  }
  return n;
}

void expectFloorUnder(const TsdfMap& s, const sim::Box& box, float min_weight,
                      const std::string& what) {
  const float voxel = s.config().voxel_size_m;
  const auto column = [&](double x) { return static_cast<int>(std::floor(x / voxel)); };
  const int x = column(box.centre_W.x()), y = column(box.centre_W.y());
  const int top = column(2.0 * box.half_extents_m.z());
  float previous = -1.0f;
  int crossing = std::numeric_limits<int>::min();
  for (int z = -2; z <= top; ++z) {
    const TsdfVoxel* v = s.findVoxel(GlobalVoxelIndex(x, y, z));
    ASSERT_TRUE(v != nullptr && v->weight >= min_weight) << what << ": S unobserved at z " << z;
    if (previous < 0.0f && v->tsdf_m >= 0.0f) crossing = z;
    previous = v->tsdf_m;
  }
  // Voxel z spans [z, z + 1) * voxel: the floor (z = 0) lies between voxels -1 and 0.
  EXPECT_EQ(crossing, 0) << what << ": S must cross zero at the floor where the box stood";
  EXPECT_GE(previous, 0.0f) << what << ": free space above the floor";
}

void fuseSession(change::ChangeDetector& detector, int session, const Dataset& dataset,
                 std::size_t count) {
  for (std::size_t i = 0; i < count && i < dataset.size(); ++i) {
    detector.integrate(session, dataset.load(i), dataset.intrinsics());
  }
}

std::shared_ptr<const sim::World> roomWorld() {
  return std::make_shared<const sim::World>(sim::World::load(sim::findWorld("room")));
}

sim::AnalyticDataset analyticSession(const std::vector<sim::Box>& extra, int frames) {
  sim::AnalyticScene scene = sim::makeDefaultScene();
  for (const sim::Box& box : extra) scene.add(box);
  sim::AnalyticDatasetConfig config;
  config.render_color = false;
  return sim::AnalyticDataset(scene, sim::makeDefaultTrajectory(frames), config);
}

MapConfig testMapConfig(float voxel_size_m, bool free_space) {
  MapConfig config;
  config.voxel_size_m = voxel_size_m;
  config.weight_mode = WeightMode::kConstant;
  config.allocate_free_space = free_space;
  return config;
}

change::ChangeConfig testChangeConfig(float voxel_size_m) {
  change::ChangeConfig config;
  config.min_weight = 2.0f;  // seen in two frames
  config.difference_threshold_m = 2.5f * voxel_size_m;
  config.merge_close_m = voxel_size_m;
  return config;
}

}  // namespace strata::test

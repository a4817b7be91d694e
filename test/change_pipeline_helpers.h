#pragma once
// Helpers of the change-pipeline tests: voxel iteration over host maps, the voxel-wise max of
// session values, comparisons, the scenes and sessions the tests run on.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "strata/change/change_detector.h"
#include "strata/io/open_dataset.h"
#include "strata/map/tsdf_map.h"
#include "strata/sim/analytic_dataset.h"
#include "strata/sim/world/world.h"

namespace strata::test {

using VoxelFn = std::function<void(const GlobalVoxelIndex&, const TsdfVoxel&)>;
void forEachVoxel(const TsdfMap& map, const VoxelFn& fn);

bool observedIn(const TsdfMap& map, const GlobalVoxelIndex& v, float min_weight);

/// Voxel-wise max of the observed values of `sessions` (weight 1 where any session observed).
TsdfMap observedMax(const std::vector<TsdfMap>& sessions, float min_weight);

/// Share of voxels observed in `expected` whose distance in `actual` differs by more than
/// `tolerance_m` (or is unobserved), and the number compared.
struct ValueComparison {
  std::size_t compared = 0;
  std::size_t over_tolerance = 0;
  std::size_t observedness_mismatches = 0;  // observed in one map only
  double share() const { return compared ? double(over_tolerance) / double(compared) : 0.0; }
};
ValueComparison compareValues(const TsdfMap& actual, const TsdfMap& expected, float tolerance_m,
                              float min_weight);

/// Fuses every frame of `dataset` in [0, count) into `session`.
void fuseSession(change::ChangeDetector& detector, int session, const Dataset& dataset,
                 std::size_t count);

/// The shipped room world.
std::shared_ptr<const sim::World> roomWorld();

/// The default analytic scene, plus `extra` boxes, seen from the default arc (no colour, exact).
sim::AnalyticDataset analyticSession(const std::vector<sim::Box>& extra, int frames);

/// Voxels of `labels` labelled dynamic within `margin_m` of the box.
std::size_t dynamicNear(const change::LabelMap& labels, const sim::Box& box, float margin_m);
/// Voxels of `labels` labelled dynamic where `session` is unobserved.
std::size_t dynamicOutside(const change::LabelMap& labels, const TsdfMap& session,
                           float min_weight);
/// Along the vertical through the box's centre, S is observed and crosses from negative to
/// positive within one voxel of the floor (z = 0), and is positive up to the box's top.
void expectFloorUnder(const TsdfMap& s, const sim::Box& box, float min_weight,
                      const std::string& what);

/// Small maps for fast tests: constant weight (one per frame), so min_weight counts frames.
MapConfig testMapConfig(float voxel_size_m, bool free_space);
change::ChangeConfig testChangeConfig(float voxel_size_m);

}  // namespace strata::test

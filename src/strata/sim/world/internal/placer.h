#pragma once
// Free-space bookkeeping for the layout generator (internal): which footprints are taken, and
// random draws of free poses inside the placement regions.
#include <optional>
#include <string>
#include <vector>

#include "strata/sim/world/internal/layout.h"
#include "strata/sim/rng.h"

namespace strata::sim {

class Placer {
 public:
  explicit Placer(const LayoutInput& input);

  /// Marks object `index` as standing at `placement` (or nowhere when not present).
  void set(int index, const Placement& placement);

  /// What a footprint of object `index` at (at, yaw) would collide with ("" when free): another
  /// object's name, "a wall or static element", "a door". `clearance_m` applies to objects and
  /// static obstacles; the object itself is ignored.
  std::string conflict(int index, const Eigen::Vector2d& at_m, double yaw_deg,
                       double clearance_m) const;

  /// A random free pose inside a region; with `from`, at least min_move_m away from it. nullopt
  /// after kMaxTries draws.
  std::optional<Placement> sample(int index, Rng& rng, const Placement* from,
                                  double min_move_m) const;

  static constexpr int kMaxTries = 400;

 private:
  const RegionSpec& pickRegion(Rng& rng) const;

  const LayoutInput& input_;
  std::vector<RegionSpec> regions_;
  std::vector<double> cumulative_area_;
  std::vector<std::optional<Footprint>> taken_;  // per object index
};

}  // namespace strata::sim

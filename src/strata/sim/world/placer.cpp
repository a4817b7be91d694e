#include "strata/sim/world/internal/placer.h"

#include <algorithm>

namespace strata::sim {
namespace {

/// The placement regions of the file, or else every room's interior.
std::vector<RegionSpec> placementRegions(const WorldSpec& spec) {
  if (!spec.regions.empty()) return spec.regions;
  std::vector<RegionSpec> regions;
  for (const RoomSpec& room : spec.rooms) regions.push_back({room.min_m, room.max_m});
  return regions;
}

}  // namespace

Placer::Placer(const LayoutInput& input)
    : input_(input),
      regions_(placementRegions(*input.spec)),
      taken_(input.half_footprints_m.size()) {
  double total = 0.0;
  for (const RegionSpec& region : regions_) {
    total += (region.max_m - region.min_m).prod();
    cumulative_area_.push_back(total);
  }
}

void Placer::set(int index, const Placement& placement) {
  taken_[index] = placement.present
                      ? std::optional<Footprint>(makeFootprint(input_.half_footprints_m[index],
                                                               placement.at_m, placement.yaw_deg))
                      : std::nullopt;
}

std::string Placer::conflict(int index, const Eigen::Vector2d& at_m, double yaw_deg,
                             double clearance_m) const {
  const Footprint f = makeFootprint(input_.half_footprints_m[index], at_m, yaw_deg);
  for (std::size_t other = 0; other < taken_.size(); ++other) {
    if (static_cast<int>(other) == index || !taken_[other]) continue;
    if (overlaps(f, *taken_[other], clearance_m)) {
      const auto& spec = *input_.spec;
      const std::size_t n = spec.objects.size();
      return other < n ? spec.objects[other].name : spec.pool[other - n].name;
    }
  }
  for (const Footprint& obstacle : input_.obstacles) {
    if (overlaps(f, obstacle, clearance_m)) return "a wall or static element";
  }
  for (const Footprint& zone : input_.door_zones) {
    if (overlaps(f, zone, 0.0)) return "a door";
  }
  return "";
}

const RegionSpec& Placer::pickRegion(Rng& rng) const {
  const double u = rng.uniform() * cumulative_area_.back();
  const auto it = std::upper_bound(cumulative_area_.begin(), cumulative_area_.end(), u);
  return regions_[std::min<std::size_t>(it - cumulative_area_.begin(), regions_.size() - 1)];
}

std::optional<Placement> Placer::sample(int index, Rng& rng, const Placement* from,
                                        double min_move_m) const {
  const double clearance = input_.spec->clearance_m;
  for (int attempt = 0; attempt < kMaxTries; ++attempt) {
    const RegionSpec& region = pickRegion(rng);
    Placement candidate;
    candidate.present = true;
    candidate.at_m.x() = rng.uniform(region.min_m.x(), region.max_m.x());
    candidate.at_m.y() = rng.uniform(region.min_m.y(), region.max_m.y());
    candidate.yaw_deg = rng.uniform(0.0, 360.0);
    if (from != nullptr && (candidate.at_m - from->at_m).norm() < min_move_m) continue;
    const Footprint f =
        makeFootprint(input_.half_footprints_m[index], candidate.at_m, candidate.yaw_deg);
    if (!inside(f, region)) continue;
    if (conflict(index, candidate.at_m, candidate.yaw_deg, clearance).empty()) return candidate;
  }
  return std::nullopt;
}

}  // namespace strata::sim

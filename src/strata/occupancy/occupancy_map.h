#pragma once
// The occupancy layer on the host: what DeviceOccupancy::download() returns and what the C++
// reference updates. Blocks of 8^3 voxels under the map's block addressing (map/block_index.h);
// only blocks with an observed voxel are kept, so two maps of the same scans hold the same blocks.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "strata/occupancy/occupancy_rules.h"
#include "strata/map/block_index.h"

namespace strata {

struct OccupancyVoxel {
  float log_odds = 0.0f;     // meaningful when state has kOccupancyObserved
  std::uint32_t state = 0u;  // kOccupancy* bits; 0 = unknown
};
using OccupancyBlock = std::array<OccupancyVoxel, kVoxelsPerBlock>;

class OccupancyMap {
 public:
  explicit OccupancyMap(float voxel_size_m) : voxel_size_m_(voxel_size_m) {}

  float voxelSize() const { return voxel_size_m_; }
  std::size_t blockCount() const { return blocks_.size(); }
  const OccupancyBlock* findBlock(const BlockIndex& b) const;
  OccupancyBlock* findBlock(const BlockIndex& b);
  /// Returns the block, allocating it (every voxel unknown) when absent.
  OccupancyBlock& allocateBlock(const BlockIndex& b);
  /// nullptr when the voxel's block is absent (the voxel is unknown).
  const OccupancyVoxel* findVoxel(const GlobalVoxelIndex& v) const;
  OccupancyClass classify(const GlobalVoxelIndex& v, const OccupancyLogOdds& l) const;

  const std::unordered_map<BlockIndex, OccupancyBlock, BlockIndexHash>& blocks() const {
    return blocks_;
  }
  /// Drops blocks without an observed voxel.
  void pruneUnobserved();

 private:
  float voxel_size_m_;
  std::unordered_map<BlockIndex, OccupancyBlock, BlockIndexHash> blocks_;
};

struct OccupancyCounts {
  std::uint64_t free = 0;
  std::uint64_t occupied = 0;
};
OccupancyCounts countOccupancy(const OccupancyMap& map, const OccupancyLogOdds& l);

/// Centres of the occupied voxels, world frame, sorted (z, y, x) so outputs are deterministic.
std::vector<Eigen::Vector3f> occupiedVoxelCentres(const OccupancyMap& map,
                                                  const OccupancyLogOdds& l);

/// Voxel-by-voxel agreement of two maps over the voxels observed in either.
struct OccupancyAgreement {
  std::uint64_t compared = 0;          // observed in a or b
  std::uint64_t class_mismatches = 0;  // unknown / free / occupied differ
  std::uint64_t log_odds_within = 0;   // observed in both, |difference| <= tolerance
  double max_abs_log_odds_difference = 0.0;
  double shareWithin() const {
    return compared == 0 ? 1.0 : static_cast<double>(log_odds_within) / compared;
  }
};
OccupancyAgreement compareOccupancy(const OccupancyMap& a, const OccupancyMap& b,
                                    const OccupancyLogOdds& l, float tolerance);

}  // namespace strata

#include "strata/occupancy/occupancy_map.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace strata {
namespace {

const OccupancyVoxel kUnknownVoxel{};

bool observed(const OccupancyVoxel& v) { return (v.state & kOccupancyObserved) != 0u; }

bool anyObserved(const OccupancyBlock& block) {
  return std::any_of(block.begin(), block.end(), observed);
}

/// Adds block `a` against `b` (either may be null: all unknown) to `out`.
void compareBlocks(const OccupancyBlock* a, const OccupancyBlock* b, const OccupancyLogOdds& l,
                   float tolerance, OccupancyAgreement& out) {
  for (int i = 0; i < kVoxelsPerBlock; ++i) {
    const OccupancyVoxel& va = a != nullptr ? (*a)[i] : kUnknownVoxel;
    const OccupancyVoxel& vb = b != nullptr ? (*b)[i] : kUnknownVoxel;
    if (!observed(va) && !observed(vb)) continue;
    ++out.compared;
    if (classifyOccupancy(va.state, va.log_odds, l) !=
        classifyOccupancy(vb.state, vb.log_odds, l)) {
      ++out.class_mismatches;
    }
    if (!observed(va) || !observed(vb)) continue;
    const double diff = std::abs(static_cast<double>(va.log_odds) - vb.log_odds);
    out.max_abs_log_odds_difference = std::max(out.max_abs_log_odds_difference, diff);
    if (diff <= tolerance) ++out.log_odds_within;
  }
}

}  // namespace

const OccupancyBlock* OccupancyMap::findBlock(const BlockIndex& b) const {
  const auto it = blocks_.find(b);
  return it == blocks_.end() ? nullptr : &it->second;
}

OccupancyBlock* OccupancyMap::findBlock(const BlockIndex& b) {
  const auto it = blocks_.find(b);
  return it == blocks_.end() ? nullptr : &it->second;
}

OccupancyBlock& OccupancyMap::allocateBlock(const BlockIndex& b) {
  return blocks_.try_emplace(b).first->second;  // OccupancyVoxel{} is unknown
}

const OccupancyVoxel* OccupancyMap::findVoxel(const GlobalVoxelIndex& v) const {
  const BlockIndex b = blockOfVoxel(v);
  const OccupancyBlock* block = findBlock(b);
  if (block == nullptr) return nullptr;
  const Eigen::Vector3i local = v - b * kBlockEdge;
  return &(*block)[linearVoxelIndex(local.x(), local.y(), local.z())];
}

OccupancyClass OccupancyMap::classify(const GlobalVoxelIndex& v, const OccupancyLogOdds& l) const {
  const OccupancyVoxel* voxel = findVoxel(v);
  return voxel == nullptr ? OccupancyClass::kUnknown
                          : classifyOccupancy(voxel->state, voxel->log_odds, l);
}

void OccupancyMap::pruneUnobserved() {
  for (auto it = blocks_.begin(); it != blocks_.end();) {
    it = anyObserved(it->second) ? std::next(it) : blocks_.erase(it);
  }
}

OccupancyCounts countOccupancy(const OccupancyMap& map, const OccupancyLogOdds& l) {
  OccupancyCounts counts;
  for (const auto& [index, block] : map.blocks()) {
    for (const OccupancyVoxel& v : block) {
      const OccupancyClass c = classifyOccupancy(v.state, v.log_odds, l);
      counts.free += c == OccupancyClass::kFree ? 1 : 0;
      counts.occupied += c == OccupancyClass::kOccupied ? 1 : 0;
    }
  }
  return counts;
}

std::vector<Eigen::Vector3f> occupiedVoxelCentres(const OccupancyMap& map,
                                                  const OccupancyLogOdds& l) {
  std::vector<GlobalVoxelIndex> voxels;
  for (const auto& [index, block] : map.blocks()) {
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const OccupancyVoxel& v = block[i];
      if (classifyOccupancy(v.state, v.log_odds, l) != OccupancyClass::kOccupied) continue;
      voxels.push_back(index * kBlockEdge + Eigen::Vector3i(i % kBlockEdge,
                                                            (i / kBlockEdge) % kBlockEdge,
                                                            i / (kBlockEdge * kBlockEdge)));
    }
  }
  std::sort(voxels.begin(), voxels.end(), [](const GlobalVoxelIndex& a, const GlobalVoxelIndex& b) {
    return std::make_tuple(a.z(), a.y(), a.x()) < std::make_tuple(b.z(), b.y(), b.x());
  });
  std::vector<Eigen::Vector3f> centres;
  centres.reserve(voxels.size());
  for (const GlobalVoxelIndex& v : voxels) centres.push_back(voxelCenter(v, map.voxelSize()));
  return centres;
}

OccupancyAgreement compareOccupancy(const OccupancyMap& a, const OccupancyMap& b,
                                    const OccupancyLogOdds& l, float tolerance) {
  OccupancyAgreement out;
  for (const auto& [index, block] : a.blocks()) {
    compareBlocks(&block, b.findBlock(index), l, tolerance, out);
  }
  for (const auto& [index, block] : b.blocks()) {
    if (a.findBlock(index) == nullptr) compareBlocks(nullptr, &block, l, tolerance, out);
  }
  return out;
}

}  // namespace strata

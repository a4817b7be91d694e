#include "strata/map/tsdf_map.h"

#include <algorithm>

namespace strata {

TsdfMap::TsdfMap(const MapConfig& config) : config_(config) { config_.validate(); }

const TsdfBlock* TsdfMap::findBlock(const BlockIndex& b) const {
  auto it = blocks_.find(b);
  return it == blocks_.end() ? nullptr : &it->second;
}

TsdfBlock* TsdfMap::findBlock(const BlockIndex& b) {
  auto it = blocks_.find(b);
  return it == blocks_.end() ? nullptr : &it->second;
}

TsdfBlock& TsdfMap::allocateBlock(const BlockIndex& b) {
  auto [it, inserted] = blocks_.try_emplace(b);
  if (inserted) it->second.fill(TsdfVoxel{});
  return it->second;
}

const TsdfVoxel* TsdfMap::findVoxel(const GlobalVoxelIndex& v) const {
  const BlockIndex b = blockOfVoxel(v);
  const TsdfBlock* block = findBlock(b);
  if (block == nullptr) return nullptr;
  const Eigen::Vector3i local = v - b * kBlockEdge;
  return &(*block)[linearVoxelIndex(local.x(), local.y(), local.z())];
}

TsdfVoxel& TsdfMap::allocateVoxel(const GlobalVoxelIndex& v) {
  const BlockIndex b = blockOfVoxel(v);
  const Eigen::Vector3i local = v - b * kBlockEdge;
  return allocateBlock(b)[linearVoxelIndex(local.x(), local.y(), local.z())];
}

std::vector<BlockIndex> TsdfMap::sortedBlockIndices() const {
  std::vector<BlockIndex> indices;
  indices.reserve(blocks_.size());
  for (const auto& [index, block] : blocks_) indices.push_back(index);
  std::sort(indices.begin(), indices.end(), [](const BlockIndex& a, const BlockIndex& b) {
    if (a.z() != b.z()) return a.z() < b.z();
    if (a.y() != b.y()) return a.y() < b.y();
    return a.x() < b.x();
  });
  return indices;
}

}  // namespace strata

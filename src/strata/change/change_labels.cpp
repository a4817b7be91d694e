#include "strata/change/change_labels.h"

namespace strata::change {
namespace {

const LabelBlock* findBlock(const LabelMap& map, const BlockIndex& b) {
  auto it = map.blocks.find(b);
  return it == map.blocks.end() ? nullptr : &it->second;
}

/// Adds the voxels of block `b` to (agree, compared).
void compareBlock(const LabelBlock* a, const LabelBlock* b, std::uint64_t& agree,
                  std::uint64_t& compared) {
  for (int i = 0; i < kVoxelsPerBlock; ++i) {
    const VoxelLabel la = a != nullptr ? (*a)[i] : VoxelLabel::kUnknown;
    const VoxelLabel lb = b != nullptr ? (*b)[i] : VoxelLabel::kUnknown;
    if (la == VoxelLabel::kUnknown && lb == VoxelLabel::kUnknown) continue;
    ++compared;
    agree += la == lb ? 1 : 0;
  }
}

}  // namespace

VoxelLabel LabelMap::label(const GlobalVoxelIndex& v) const {
  const BlockIndex b = blockOfVoxel(v);
  const LabelBlock* block = findBlock(*this, b);
  if (block == nullptr) return VoxelLabel::kUnknown;
  const Eigen::Vector3i local = v - b * kBlockEdge;
  return (*block)[linearVoxelIndex(local.x(), local.y(), local.z())];
}

LabelBlock& LabelMap::allocateBlock(const BlockIndex& b) {
  auto [it, inserted] = blocks.try_emplace(b);
  if (inserted) it->second.fill(VoxelLabel::kUnknown);
  return it->second;
}

std::uint64_t LabelMap::count(VoxelLabel label) const {
  std::uint64_t n = 0;
  for (const auto& [index, block] : blocks) {
    for (const VoxelLabel l : block) n += l == label ? 1 : 0;
  }
  return n;
}

double labelAgreement(const LabelMap& a, const LabelMap& b) {
  std::uint64_t agree = 0, compared = 0;
  for (const auto& [index, block] : a.blocks) {
    compareBlock(&block, findBlock(b, index), agree, compared);
  }
  for (const auto& [index, block] : b.blocks) {
    if (findBlock(a, index) == nullptr) compareBlock(nullptr, &block, agree, compared);
  }
  return compared == 0 ? 1.0 : static_cast<double>(agree) / static_cast<double>(compared);
}

}  // namespace strata::change

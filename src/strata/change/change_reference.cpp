#include "strata/change/change_reference.h"

#include <vector>

#include "strata/core/parallel_for.h"

namespace strata::change {
namespace {

const TsdfVoxel kUnobserved{};

/// Runs fn(i) for i in [0, n) on two threads (blocks are independent).
template <typename Fn>
void parallelFor(std::size_t n, Fn fn) {
  parallelForEach(n, 2, fn);
}

/// Blocks of both maps (each once).
std::vector<BlockIndex> unionBlocks(const TsdfMap& a, const TsdfMap& b) {
  std::vector<BlockIndex> out = a.sortedBlockIndices();
  for (const BlockIndex& index : b.sortedBlockIndices()) {
    if (a.findBlock(index) == nullptr) out.push_back(index);
  }
  return out;
}

/// Applies rule(voxel of a, voxel of b) over the union of both maps' blocks.
template <typename Rule>
LabelMap voxelwise(const TsdfMap& a, const TsdfMap& b, Rule rule) {
  LabelMap out;
  out.voxel_size_m = a.config().voxel_size_m;
  const std::vector<BlockIndex> blocks = unionBlocks(a, b);
  std::vector<LabelBlock*> targets;
  for (const BlockIndex& index : blocks) targets.push_back(&out.allocateBlock(index));
  parallelFor(blocks.size(), [&](std::size_t i) {
    const TsdfBlock* block_a = a.findBlock(blocks[i]);
    const TsdfBlock* block_b = b.findBlock(blocks[i]);
    for (int v = 0; v < kVoxelsPerBlock; ++v) {
      (*targets[i])[v] = rule(block_a != nullptr ? (*block_a)[v] : kUnobserved,
                              block_b != nullptr ? (*block_b)[v] : kUnobserved);
    }
  });
  return out;
}

/// 0/1 dynamic indicators of `in` over block `index` and an r-voxel border, edge 8 + 2r, x
/// fastest. r <= 3, so the 3x3x3 blocks around `index` hold the tile.
std::vector<int> dynamicTile(const LabelMap& in, const BlockIndex& index, int r) {
  const LabelBlock* around[27];
  for (int n = 0; n < 27; ++n) {
    const BlockIndex b = index + Eigen::Vector3i(n % 3 - 1, n / 3 % 3 - 1, n / 9 - 1);
    auto it = in.blocks.find(b);
    around[n] = it != in.blocks.end() ? &it->second : nullptr;
  }
  const int edge = kBlockEdge + 2 * r;
  std::vector<int> tile(static_cast<std::size_t>(edge) * edge * edge, 0);
  for (int z = 0; z < edge; ++z) {
    for (int y = 0; y < edge; ++y) {
      for (int x = 0; x < edge; ++x) {
        const Eigen::Vector3i local(x - r, y - r, z - r);  // relative to the block's origin
        const Eigen::Vector3i offset(floorDiv(local.x(), kBlockEdge),
                                     floorDiv(local.y(), kBlockEdge),
                                     floorDiv(local.z(), kBlockEdge));
        const LabelBlock* block =
            around[(offset.x() + 1) + 3 * (offset.y() + 1) + 9 * (offset.z() + 1)];
        if (block == nullptr) continue;
        const Eigen::Vector3i inner = local - offset * kBlockEdge;
        tile[(z * edge + y) * edge + x] =
            (*block)[linearVoxelIndex(inner.x(), inner.y(), inner.z())] == VoxelLabel::kDynamic;
      }
    }
  }
  return tile;
}

/// Number of dynamic voxels of `in` in the kernel^3 cube around each voxel of block `index`.
std::vector<int> dynamicInCubes(const LabelMap& in, const BlockIndex& index, int kernel_voxels) {
  const int edge = kBlockEdge + 2 * (kernel_voxels / 2);
  const std::vector<int> tile = dynamicTile(in, index, kernel_voxels / 2);
  std::vector<int> counts(kVoxelsPerBlock, 0);
  for (int z = 0; z < kBlockEdge; ++z) {
    for (int y = 0; y < kBlockEdge; ++y) {
      for (int x = 0; x < kBlockEdge; ++x) {
        int n = 0;  // the cube centred on (x, y, z) is tile [x, x + 2r] etc.
        for (int dz = 0; dz < kernel_voxels; ++dz) {
          for (int dy = 0; dy < kernel_voxels; ++dy) {
            for (int dx = 0; dx < kernel_voxels; ++dx) {
              n += tile[((z + dz) * edge + (y + dy)) * edge + (x + dx)];
            }
          }
        }
        counts[linearVoxelIndex(x, y, z)] = n;
      }
    }
  }
  return counts;
}

/// out[b][v] = rule(raw[b][v], dynamic count of `counted` around v) over raw's blocks.
template <typename Rule>
LabelMap cubeFilter(const LabelMap& raw, const LabelMap& counted, int kernel_voxels, Rule rule) {
  LabelMap out;
  out.voxel_size_m = raw.voxel_size_m;
  std::vector<std::pair<const BlockIndex*, const LabelBlock*>> sources;
  std::vector<LabelBlock*> targets;
  for (const auto& [index, block] : raw.blocks) {
    sources.emplace_back(&index, &block);
    targets.push_back(&out.allocateBlock(index));
  }
  parallelFor(sources.size(), [&](std::size_t i) {
    const std::vector<int> counts = dynamicInCubes(counted, *sources[i].first, kernel_voxels);
    for (int v = 0; v < kVoxelsPerBlock; ++v)
      (*targets[i])[v] = rule((*sources[i].second)[v], counts[v]);
  });
  return out;
}

}  // namespace

LabelMap differenceReference(const TsdfMap& s, const TsdfMap& m, const ChangeConfig& config) {
  return voxelwise(s, m, [&](const TsdfVoxel& vs, const TsdfVoxel& vm) {
    return differenceLabel(vs, vm, config);
  });
}

LabelMap sessionDynamicRawReference(const TsdfMap& m, const TsdfMap& s,
                                    const ChangeConfig& config) {
  return voxelwise(m, s, [&](const TsdfVoxel& vm, const TsdfVoxel& vs) {
    return sessionDynamicLabel(vm, vs, config);
  });
}

LabelMap erodeReference(const LabelMap& raw, int kernel_voxels) {
  return cubeFilter(raw, raw, kernel_voxels, [&](VoxelLabel label, int count) {
    return erodedLabel(label, count, kernel_voxels);
  });
}

LabelMap dilateReference(const LabelMap& raw, const LabelMap& eroded, int kernel_voxels,
                         DilationMask mask) {
  return cubeFilter(raw, eroded, kernel_voxels,
                    [&](VoxelLabel label, int count) { return dilatedLabel(label, count, mask); });
}

LabelMap cleanLabelsReference(const LabelMap& raw, const ChangeConfig& config, DilationMask mask) {
  const LabelMap eroded = erodeReference(raw, config.erosion_kernel_voxels);
  return dilateReference(raw, eroded, config.dilation_kernel_voxels, mask);
}

void staticUpdateReference(TsdfMap& s, const TsdfMap& m, const LabelMap& d,
                           const ChangeConfig& config) {
  const std::vector<BlockIndex> blocks = m.sortedBlockIndices();
  std::vector<TsdfBlock*> targets;
  for (const BlockIndex& index : blocks) targets.push_back(&s.allocateBlock(index));
  const float max_weight = s.config().max_weight;
  parallelFor(blocks.size(), [&](std::size_t i) {
    const TsdfBlock& block_m = *m.findBlock(blocks[i]);
    auto labels = d.blocks.find(blocks[i]);
    for (int v = 0; v < kVoxelsPerBlock; ++v) {
      const VoxelLabel label = labels != d.blocks.end() ? labels->second[v] : VoxelLabel::kUnknown;
      (*targets[i])[v] = mergeStatic((*targets[i])[v], block_m[v], label, config, max_weight);
    }
  });
}

}  // namespace strata::change

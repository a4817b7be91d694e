// computeEsdfReference: the exact nearest site of every voxel of every allocated block, by brute
// force over the sites bucketed per block, searched in growing rings of blocks. Deliberately a
// different algorithm from the device's separable transform, so the tests hold one to the other.
#include <algorithm>
#include <array>
#include <unordered_map>
#include <vector>

#include "strata/esdf/esdf.h"
#include "strata/esdf/esdf_rules.h"
#include "strata/core/parallel_for.h"

namespace strata {
namespace {

using SiteBuckets = std::unordered_map<BlockIndex, std::vector<GlobalVoxelIndex>, BlockIndexHash>;

/// Best squared distance and nearest site of each voxel of one block (x fastest).
struct BlockSearch {
  std::array<int, kVoxelsPerBlock> x{}, y{}, z{};
  std::array<std::uint32_t, kVoxelsPerBlock> best_d2{};
  std::array<GlobalVoxelIndex, kVoxelsPerBlock> site{};
};

SiteBuckets bucketSites(const TsdfMap& tsdf, const EsdfConfig& config) {
  SiteBuckets buckets;
  const float voxel_size_m = tsdf.config().voxel_size_m;
  for (const auto& [b, block] : tsdf.blocks()) {
    std::vector<GlobalVoxelIndex> sites;
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      if (!isEsdfSite(block[i], config, voxel_size_m)) continue;
      sites.emplace_back(b * kBlockEdge + GlobalVoxelIndex(i % kBlockEdge,
                                                           (i / kBlockEdge) % kBlockEdge,
                                                           i / (kBlockEdge * kBlockEdge)));
    }
    if (!sites.empty()) buckets.emplace(b, std::move(sites));
  }
  return buckets;
}

void offerSites(const std::vector<GlobalVoxelIndex>& sites, BlockSearch& s) {
  for (const GlobalVoxelIndex& p : sites) {
    // Plain arrays so the compiler vectorises the 512-voxel loop.
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const int dx = s.x[i] - p.x(), dy = s.y[i] - p.y(), dz = s.z[i] - p.z();
      const auto d2 = static_cast<std::uint32_t>(dx * dx + dy * dy + dz * dz);
      if (d2 < s.best_d2[i]) {
        s.best_d2[i] = d2;
        s.site[i] = p;
      }
    }
  }
}

/// Offers the sites of every block at Chebyshev block distance exactly r from b.
void searchRing(const BlockIndex& b, int r, const SiteBuckets& buckets, BlockSearch& s) {
  for (int dz = -r; dz <= r; ++dz) {
    for (int dy = -r; dy <= r; ++dy) {
      for (int dx = -r; dx <= r; ++dx) {
        if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != r) continue;
        const auto it = buckets.find(b + BlockIndex(dx, dy, dz));
        if (it != buckets.end()) offerSites(it->second, s);
      }
    }
  }
}

EsdfBlock esdfOfBlock(const BlockIndex& b, const TsdfBlock& tsdf, const SiteBuckets& buckets,
                      const EsdfConfig& config, float voxel_size_m) {
  const EsdfReach reach = esdfReach(config, voxel_size_m);
  BlockSearch s;
  for (int i = 0; i < kVoxelsPerBlock; ++i) {
    s.x[i] = b.x() * kBlockEdge + i % kBlockEdge;
    s.y[i] = b.y() * kBlockEdge + (i / kBlockEdge) % kBlockEdge;
    s.z[i] = b.z() * kBlockEdge + i / (kBlockEdge * kBlockEdge);
    s.best_d2[i] = reach.max_d2 + 1;  // "no site within reach"
  }
  for (int r = 0;; ++r) {
    searchRing(b, r, buckets, s);
    // A site in ring r + 1 or farther is at least r * 8 + 1 voxels away along some axis.
    const std::uint32_t worst = *std::max_element(s.best_d2.begin(), s.best_d2.end());
    const auto gap = static_cast<std::uint32_t>(r * kBlockEdge + 1);
    if (gap * gap >= worst) break;
  }
  EsdfBlock out;
  for (int i = 0; i < kVoxelsPerBlock; ++i) {
    const bool has_site = s.best_d2[i] <= reach.max_d2;
    const GlobalVoxelIndex v(s.x[i], s.y[i], s.z[i]);
    out[i] = makeEsdfVoxel(tsdf[i], has_site,
                           has_site ? GlobalVoxelIndex(s.site[i] - v) : GlobalVoxelIndex::Zero(),
                           config, voxel_size_m);
  }
  return out;
}

}  // namespace

EsdfMap computeEsdfReference(const TsdfMap& tsdf, const EsdfConfig& config) {
  const float voxel_size_m = tsdf.config().voxel_size_m;
  config.validate(voxel_size_m);
  const SiteBuckets buckets = bucketSites(tsdf, config);
  const std::vector<BlockIndex> indices = tsdf.sortedBlockIndices();
  std::vector<EsdfBlock> blocks(indices.size());
  parallelForChunks(
      indices.size(), resolveThreadCount(0), 8, [&](std::size_t begin, std::size_t end) {
        for (std::size_t i = begin; i < end; ++i) {
          blocks[i] =
              esdfOfBlock(indices[i], *tsdf.findBlock(indices[i]), buckets, config, voxel_size_m);
        }
      });
  EsdfMap out;
  out.voxel_size_m = voxel_size_m;
  out.config = config;
  for (std::size_t i = 0; i < indices.size(); ++i) out.blocks.emplace(indices[i], blocks[i]);
  return out;
}

}  // namespace strata

// The host reference of shaders/explore/view_gain.comp: the same fixed-point march, the same
// integer volumes, so results are equal.
#include <cstdint>
#include <vector>

#include "strata/explore/internal/view_gain_rays.h"
#include "strata/explore/view_gain.h"

namespace strata::explore {
namespace {

using internal::FixedPosition;
using internal::ViewGainRays;

/// The host map seen voxel by voxel, remembering the last block (rays stay in one for a while).
class VoxelReader {
 public:
  explicit VoxelReader(const TsdfMap& map) : map_(map) {}

  /// nullptr when the block is not allocated.
  const TsdfVoxel* voxel(const Eigen::Vector3i& v) {
    const BlockIndex block(v.x() >> 3, v.y() >> 3, v.z() >> 3);
    if (!has_block_ || block != block_) {
      block_ = block;
      has_block_ = true;
      data_ = map_.findBlock(block);
    }
    if (data_ == nullptr) return nullptr;
    return &(*data_)[linearVoxelIndex(v.x() & 7, v.y() & 7, v.z() & 7)];
  }

 private:
  const TsdfMap& map_;
  BlockIndex block_ = BlockIndex::Zero();
  bool has_block_ = false;
  const TsdfBlock* data_ = nullptr;
};

/// Unknown volume (units) ray `ray` sees from `origin`.
std::uint64_t marchRay(VoxelReader& reader, const ViewGainRays& rays, const FixedPosition& origin,
                       int ray, float min_weight, float occupied_below_m) {
  const Eigen::Vector4i& dir_q = rays.dir_q[ray];
  const std::uint32_t* weight =
      rays.weight.data() + static_cast<std::size_t>(dir_q[3]) * rays.steps;
  std::uint64_t sum = 0;
  for (int k = 0; k < rays.steps; ++k) {
    const TsdfVoxel* voxel = reader.voxel(internal::stepVoxel(origin, dir_q, rays.t_q[k]));
    if (voxel == nullptr || !(voxel->weight >= min_weight)) {
      sum += weight[k];
    } else if (internal::stopsRay(voxel->tsdf_m, voxel->weight, min_weight, occupied_below_m)) {
      break;
    }
  }
  return sum;
}

}  // namespace

std::vector<ViewGain> viewGainReference(const TsdfMap& map, const ViewGainConfig& config,
                                        const std::vector<Eigen::Vector3f>& positions_W) {
  const float voxel_size_m = map.config().voxel_size_m;
  const ViewGainRays rays = internal::makeViewGainRays(config, voxel_size_m);
  const float occupied_below_m = 0.5f * voxel_size_m;
  std::vector<FixedPosition> origins;
  origins.reserve(positions_W.size());
  for (const Eigen::Vector3f& p : positions_W) {
    origins.push_back(internal::fixedPosition(p, voxel_size_m));
  }
  std::vector<ViewGain> gains;
  gains.reserve(positions_W.size());
  std::vector<std::uint64_t> bins(config.yaw_bins);
  VoxelReader reader(map);
  for (const FixedPosition& origin : origins) {
    for (int b = 0; b < config.yaw_bins; ++b) {
      bins[b] = 0;
      for (int r = b * rays.bin_rays; r < (b + 1) * rays.bin_rays; ++r) {
        bins[b] += marchRay(reader, rays, origin, r, config.min_weight, occupied_below_m);
      }
    }
    gains.push_back(internal::finishViewGain(bins.data(), rays, config));
  }
  return gains;
}

}  // namespace strata::explore

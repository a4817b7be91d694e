#pragma once
// DeviceChange internals shared by change_device.cpp and change_device_passes.cpp.
#include <algorithm>
#include <cstdint>

#include "strata/change/change_device.h"
#include "strata/change/change_layout.h"
#include "strata/vk/dispatch_size.h"

namespace strata::change {

using vk::kMaxGroupsPerDimension;
inline constexpr std::uint32_t kNeighbours = 27;
inline constexpr std::uint32_t kRowsPerBlock = 64;  // dynamic row masks (change_rows.glsl)
inline constexpr std::uint32_t kBlocksPerMorphGroup = 4;
// Counters: D raw, eroded, dilated; then the same three for each session part.
inline constexpr std::uint32_t kCountersPerClean = 3;

// Timestamps written after each stage.
enum Stamp : std::uint32_t {
  kStart,
  kNeighbourTable,
  kDifference,
  kErosion,
  kDilation,
  kStaticUpdate,
  kSessionParts,
  kStamps
};

using vk::divideUp;

inline void dispatchLinear(vk::CommandBuffer& cmd, std::uint64_t groups) {
  const auto x =
      static_cast<std::uint32_t>(std::min<std::uint64_t>(groups, kMaxGroupsPerDimension));
  cmd.dispatch(x, static_cast<std::uint32_t>(divideUp(groups, x)));
}

struct DeviceChange::Pipelines {
  Pipelines(vk::Context& context, const ChangeConfig& config, bool by_address) {
    const std::uint32_t address = by_address ? 1u : 0u;
    auto voxelPass = [&](const char* name) {
      return vk::ComputePipeline::create(context, name, 5, sizeof(gpu::ChangeVoxelPush), {address});
    };
    difference = voxelPass("change_difference");
    session_dynamic = voxelPass("change_session_dynamic");
    static_update = voxelPass("change_static_update");
    erode = vk::ComputePipeline::create(context, "change_erode", 5, sizeof(gpu::ChangeMorphPush),
                                        {static_cast<std::uint32_t>(config.erosion_kernel_voxels)});
    dilate = vk::ComputePipeline::create(
        context, "change_dilate", 6, sizeof(gpu::ChangeMorphPush),
        {static_cast<std::uint32_t>(config.dilation_kernel_voxels), address});
  }
  vk::ComputePipeline difference, session_dynamic, static_update, erode, dilate;
};

}  // namespace strata::change

#pragma once
// One compute dispatch between two timestamps, submitted and waited for: the shape of every
// single-pass kernel (raycast, ESDF queries, the sample kernels of keyframe selection). The
// multi-pass kernels (fusion, change, occupancy) record several passes into one command buffer.
#include <cstddef>
#include <cstdint>

#include "strata/vk/vk.h"

namespace strata {

/// Binds `pipeline` with `set` and `push`, dispatches groups_x x groups_y workgroups, waits;
/// returns the device time in milliseconds.
double dispatchTimed(vk::Context& context, const vk::ComputePipeline& pipeline,
                     const vk::DescriptorSet& set, const void* push, std::size_t push_bytes,
                     std::uint32_t groups_x, std::uint32_t groups_y, vk::TimestampQueries& timer);

}  // namespace strata

// Device dispatch of shaders/sample_differences.comp.
#include "strata/select/select_differences.h"

#include <cstring>
#include <string>

#include "strata/core/error.h"
#include "strata/select/internal/select_layout.h"
#include "strata/vk/timed_dispatch.h"

namespace strata {

SampleDifferenceKernel::SampleDifferenceKernel(vk::Context& context)
    : context_(context),
      pipeline_(vk::ComputePipeline::create(context, "sample_differences", 3,
                                            sizeof(gpu::SampleDifferencePush))),
      timer_(vk::TimestampQueries::create(context, 2)) {}

void SampleDifferenceKernel::ensureCapacity(std::size_t sample_count) {
  if (sample_count <= capacity_) return;
  keyframe_in_ = vk::Buffer::create(context_, sample_count * 8, vk::MemoryUsage::kHostUpload,
                                    "keyframe at samples");
  differences_out_ = vk::Buffer::create(context_, sample_count * 8, vk::MemoryUsage::kHostReadback,
                                        "sample differences");
  capacity_ = sample_count;
}

SampleDifferences SampleDifferenceKernel::run(
    const SampleRaycastKernel& raycast, const SampleGrid& grid, const std::vector<float>& depth_m,
    const std::vector<std::uint32_t>& color_rgb, bool has_color,
    const SampleDifferenceOptions& options, double* device_ms) {
  const std::size_t n = static_cast<std::size_t>(grid.count());
  if (depth_m.size() != n || color_rgb.size() != n) {
    throw InputError("sample differences: keyframe samples do not fit the " +
                     std::to_string(grid.width) + "x" + std::to_string(grid.height) + " grid");
  }
  ensureCapacity(n);
  // Explicit host->device copy: interleaved (depth bits, colour) per sample.
  auto* words = static_cast<std::uint32_t*>(keyframe_in_.mapped());
  for (std::size_t i = 0; i < n; ++i) {
    std::memcpy(&words[2 * i], &depth_m[i], 4);
    words[2 * i + 1] = color_rgb[i];
  }

  gpu::SampleDifferencePush push{};
  push.grid_size[0] = static_cast<std::uint32_t>(grid.width);
  push.grid_size[1] = static_cast<std::uint32_t>(grid.height);
  push.depth_tolerance_m = options.depth_tolerance_m;
  push.max_depth_difference_m = options.max_depth_difference_m;
  push.has_color = has_color ? 1u : 0u;

  vk::DescriptorSet set = vk::DescriptorSet::create(
      context_, pipeline_, {&raycast.samplesBuffer(), &keyframe_in_, &differences_out_});
  const double ms =
      dispatchTimed(context_, pipeline_, set, &push, sizeof(push), (push.grid_size[0] + 15) / 16,
                    (push.grid_size[1] + 15) / 16, timer_);
  if (device_ms != nullptr) *device_ms = ms;

  SampleDifferences out;
  out.color.resize(n);
  out.depth_m.resize(n);
  const auto* result = static_cast<const float*>(differences_out_.mapped());
  for (std::size_t i = 0; i < n; ++i) {
    out.color[i] = result[2 * i];
    out.depth_m[i] = result[2 * i + 1];
  }
  return out;
}

}  // namespace strata

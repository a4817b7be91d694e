#include "streaming_ceiling.h"

#include <algorithm>
#include <cstdint>
#include <vector>

namespace strata::bench {

StreamingCeiling measureStreamingCeiling(vk::Context& context, double buffer_mib,
                                         int repetitions) {
  const auto bytes = static_cast<std::uint64_t>(buffer_mib * 1024.0 * 1024.0) / 16 * 16;
  const auto count = static_cast<std::uint32_t>(bytes / 16);
  vk::Buffer src = vk::Buffer::create(context, bytes, vk::MemoryUsage::kDeviceLocal, "ceiling src");
  vk::Buffer dst = vk::Buffer::create(context, bytes, vk::MemoryUsage::kDeviceLocal, "ceiling dst");
  vk::ComputePipeline pipeline = vk::ComputePipeline::create(context, "stream_copy", 2, 4);
  vk::DescriptorSet set = vk::DescriptorSet::create(context, pipeline, {&src, &dst});
  vk::TimestampQueries timer = vk::TimestampQueries::create(context, 2);
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context);
  const std::uint32_t groups = (count + 255) / 256;
  const std::uint32_t groups_x = std::min<std::uint32_t>(groups, 65535);
  std::vector<double> gb_per_s;
  for (int r = 0; r <= repetitions; ++r) {
    cmd.begin();
    if (r == 0) cmd.fill(src, 0x3f800000u);  // 1.0f everywhere: real data to move
    cmd.barrier();
    cmd.resetQueries(timer);
    cmd.writeTimestamp(timer, 0);
    cmd.bind(pipeline, set);
    cmd.pushConstants(pipeline, &count, sizeof(count));
    cmd.dispatch(groups_x, (groups + groups_x - 1) / groups_x);
    cmd.barrier();
    cmd.writeTimestamp(timer, 1);
    cmd.end();
    cmd.submitAndWait();
    const double ms = timer.elapsedMs(0, 1);
    if (r > 0 && ms > 0.0) gb_per_s.push_back(2.0 * static_cast<double>(bytes) / (ms * 1e6));
  }
  StreamingCeiling result;
  result.buffer_mib = static_cast<double>(bytes) / (1024.0 * 1024.0);
  result.repetitions = static_cast<int>(gb_per_s.size());
  if (!gb_per_s.empty()) {
    std::sort(gb_per_s.begin(), gb_per_s.end());
    result.gb_per_s = gb_per_s[gb_per_s.size() / 2];
  }
  return result;
}

}  // namespace strata::bench

#include "strata/vk/timed_dispatch.h"

namespace strata {

double dispatchTimed(vk::Context& context, const vk::ComputePipeline& pipeline,
                     const vk::DescriptorSet& set, const void* push, std::size_t push_bytes,
                     std::uint32_t groups_x, std::uint32_t groups_y, vk::TimestampQueries& timer) {
  vk::CommandBuffer cmd = vk::CommandBuffer::create(context);
  cmd.begin();
  cmd.resetQueries(timer);
  cmd.writeTimestamp(timer, 0);
  cmd.bind(pipeline, set);
  cmd.pushConstants(pipeline, push, push_bytes);
  cmd.dispatch(groups_x, groups_y);
  cmd.barrier();
  cmd.writeTimestamp(timer, 1);
  cmd.end();
  cmd.submitAndWait();
  return timer.elapsedMs(0, 1);
}

}  // namespace strata

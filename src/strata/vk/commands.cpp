// CommandBuffer: record compute work, submit to the context's queue, wait on its own fence.
#include <utility>

#include "strata/core/error.h"
#include "strata/vk/internal/context_impl.h"
#include "strata/vk/internal/result.h"
#include "strata/vk/transfer.h"

namespace strata::vk {
namespace {

// Generous: one submit of a large map on lavapipe takes seconds; ten minutes means a hang.
constexpr std::uint64_t kSubmitTimeout_ns = 600ull * 1000 * 1000 * 1000;

void checkSubmit(VkResult result, const char* call) {
  if (result == VK_ERROR_DEVICE_LOST) {
    throw DeviceError(std::string("Vulkan device lost during ") + call +
                      " (command buffer submit); the host copy of the map is intact; restart "
                      "with --device to pick another device or update the driver");
  }
  if (result == VK_TIMEOUT) {
    throw DeviceError(std::string("Vulkan command buffer did not finish within ") +
                      std::to_string(kSubmitTimeout_ns / 1000000000ull) + " s (" + call +
                      "); the device is probably hung; the host copy of the map is intact; "
                      "restart with --device to pick another device or update the driver");
  }
  check(result, call);
}

}  // namespace

CommandBuffer CommandBuffer::create(Context& context) {
  const Dispatch& vk = dispatchOf(context);
  // Filled step by step; if a step throws, ~CommandBuffer releases what was made.
  CommandBuffer c;
  c.context_ = &context;
  noteCreated(context);
  VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  info.commandPool = context.commandPool();
  info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  info.commandBufferCount = 1;
  check(vk.vkAllocateCommandBuffers(context.device(), &info, &c.command_buffer_),
        "vkAllocateCommandBuffers");
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vk.vkCreateFence(context.device(), &fence_info, nullptr, &c.fence_), "vkCreateFence");
  return c;
}

CommandBuffer::~CommandBuffer() { release(); }

CommandBuffer::CommandBuffer(CommandBuffer&& other) noexcept { *this = std::move(other); }

CommandBuffer& CommandBuffer::operator=(CommandBuffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    command_buffer_ = std::exchange(other.command_buffer_, VK_NULL_HANDLE);
    fence_ = std::exchange(other.fence_, VK_NULL_HANDLE);
  }
  return *this;
}

void CommandBuffer::release() {
  if (context_ == nullptr) return;
  const Dispatch& vk = dispatchOf(*context_);
  const VkDevice device = context_->device();
  if (command_buffer_ != VK_NULL_HANDLE) {
    vk.vkFreeCommandBuffers(device, context_->commandPool(), 1, &command_buffer_);
  }
  if (fence_ != VK_NULL_HANDLE) vk.vkDestroyFence(device, fence_, nullptr);
  noteDestroyed(*context_);
  context_ = nullptr;
  command_buffer_ = VK_NULL_HANDLE;
  fence_ = VK_NULL_HANDLE;
}

void CommandBuffer::begin() {
  // The pool has RESET_COMMAND_BUFFER, so beginning again implicitly resets the last recording.
  VkCommandBufferBeginInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(dispatchOf(*context_).vkBeginCommandBuffer(command_buffer_, &info), "vkBeginCommandBuffer");
}

void CommandBuffer::bind(const ComputePipeline& pipeline, const DescriptorSet& set) {
  const Dispatch& vk = dispatchOf(*context_);
  vk.vkCmdBindPipeline(command_buffer_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.pipeline());
  const VkDescriptorSet handle = set.handle();
  vk.vkCmdBindDescriptorSets(command_buffer_, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.layout(), 0,
                             1, &handle, 0, nullptr);
}

void CommandBuffer::pushConstants(const ComputePipeline& pipeline, const void* data,
                                  std::size_t bytes) {
  // Checked here too: outside validation runs a wrong size would silently feed the shader garbage.
  if (bytes % 4 != 0 || bytes > pipeline.pushConstantBytes()) {
    throw Error("push constants for shader '" + pipeline.name() + "': " + std::to_string(bytes) +
                " bytes given; need a multiple of 4 and at most the pipeline's " +
                std::to_string(pipeline.pushConstantBytes()));
  }
  if (bytes == 0) return;
  dispatchOf(*context_).vkCmdPushConstants(command_buffer_, pipeline.layout(),
                                           VK_SHADER_STAGE_COMPUTE_BIT, 0,
                                           static_cast<std::uint32_t>(bytes), data);
}

void CommandBuffer::dispatch(std::uint32_t groups_x, std::uint32_t groups_y,
                             std::uint32_t groups_z) {
  dispatchOf(*context_).vkCmdDispatch(command_buffer_, groups_x, groups_y, groups_z);
}

void CommandBuffer::dispatchIndirect(const Buffer& args, VkDeviceSize offset_bytes) {
  requireRange(*context_, args, offset_bytes, 12, "dispatchIndirect (arguments)");
  dispatchOf(*context_).vkCmdDispatchIndirect(command_buffer_, args.handle(), offset_bytes);
}

void CommandBuffer::barrier() {
  // NOTE: one global memory barrier rather than per-buffer ones: simpler, and on the devices
  // Strata targets the cost is the execution dependency, which buffer barriers would not avoid.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                          VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT |
                          VK_ACCESS_HOST_READ_BIT | VK_ACCESS_HOST_WRITE_BIT |
                          VK_ACCESS_INDIRECT_COMMAND_READ_BIT;
  dispatchOf(*context_).vkCmdPipelineBarrier(
      command_buffer_, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
      VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
          VK_PIPELINE_STAGE_HOST_BIT | VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
      0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void CommandBuffer::copy(const Buffer& src, Buffer& dst, VkDeviceSize bytes,
                         VkDeviceSize src_offset, VkDeviceSize dst_offset) {
  requireRange(*context_, src, src_offset, bytes, "copy (source)");
  requireRange(*context_, dst, dst_offset, bytes, "copy (destination)");
  if (bytes == 0) return;  // a zero-sized region is invalid Vulkan
  const VkBufferCopy region{src_offset, dst_offset, bytes};
  dispatchOf(*context_).vkCmdCopyBuffer(command_buffer_, src.handle(), dst.handle(), 1, &region);
}

void CommandBuffer::fill(Buffer& buffer, std::uint32_t value, VkDeviceSize offset,
                         VkDeviceSize bytes) {
  dispatchOf(*context_).vkCmdFillBuffer(command_buffer_, buffer.handle(), offset, bytes, value);
}

void CommandBuffer::resetQueries(TimestampQueries& queries) {
  dispatchOf(*context_).vkCmdResetQueryPool(command_buffer_, queries.handle(), 0, queries.count());
}

void CommandBuffer::writeTimestamp(TimestampQueries& queries, std::uint32_t index) {
  // Bottom of pipe: the time when every earlier command has finished.
  dispatchOf(*context_).vkCmdWriteTimestamp(command_buffer_, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                                            queries.handle(), index);
}

void CommandBuffer::end() {
  check(dispatchOf(*context_).vkEndCommandBuffer(command_buffer_), "vkEndCommandBuffer");
}

void CommandBuffer::submitAndWait() {
  const Dispatch& vk = dispatchOf(*context_);
  const VkDevice device = context_->device();
  check(vk.vkResetFences(device, 1, &fence_), "vkResetFences");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &command_buffer_;
  checkSubmit(vk.vkQueueSubmit(context_->queue(), 1, &submit, fence_), "vkQueueSubmit");
  checkSubmit(vk.vkWaitForFences(device, 1, &fence_, VK_TRUE, kSubmitTimeout_ns),
              "vkWaitForFences");
}

}  // namespace strata::vk

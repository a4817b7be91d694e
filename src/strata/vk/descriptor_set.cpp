// DescriptorSet: one set with its own pool, binding buffers to a pipeline's set 0 in order.
#include <algorithm>
#include <utility>

#include "strata/core/error.h"
#include "strata/vk/internal/context_impl.h"
#include "strata/vk/internal/result.h"
#include "strata/vk/transfer.h"

namespace strata::vk {
namespace {

void requireBuffers(const Context& context, const ComputePipeline& pipeline,
                    const std::vector<const Buffer*>& buffers) {
  const std::string subject = "descriptor set for shader '" + pipeline.name() + "'";
  if (buffers.size() != pipeline.storageBufferCount()) {
    throw Error(subject + ": " + std::to_string(buffers.size()) +
                " buffers given, the pipeline has " +
                std::to_string(pipeline.storageBufferCount()) + " storage-buffer bindings");
  }
  for (std::size_t i = 0; i < buffers.size(); ++i) {
    if (buffers[i] == nullptr || !buffers[i]->valid()) {
      throw Error(subject + ": binding " + std::to_string(i) + " has no buffer");
    }
    if (BufferAccess::context(*buffers[i]) != &context) {
      throw Error(subject + ": buffer '" + buffers[i]->name() + "' belongs to another context");
    }
  }
}

VkDescriptorPool createPool(const Context& context, std::uint32_t storage_buffer_count) {
  // NOTE: at least one descriptor per pool size, so a pipeline without buffers still works.
  const VkDescriptorPoolSize size{VK_DESCRIPTOR_TYPE_STORAGE_BUFFER,
                                  std::max<std::uint32_t>(storage_buffer_count, 1)};
  VkDescriptorPoolCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  info.maxSets = 1;
  info.poolSizeCount = 1;
  info.pPoolSizes = &size;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  check(dispatchOf(context).vkCreateDescriptorPool(context.device(), &info, nullptr, &pool),
        "vkCreateDescriptorPool");
  return pool;
}

void writeBindings(const Context& context, VkDescriptorSet set,
                   const std::vector<const Buffer*>& buffers) {
  // One binding sees at most maxStorageBufferRange bytes; larger pools use device addresses.
  const VkDeviceSize max_range = context.limits().max_storage_buffer_range_bytes;
  std::vector<VkDescriptorBufferInfo> infos(buffers.size());
  std::vector<VkWriteDescriptorSet> writes(buffers.size());
  for (std::uint32_t i = 0; i < buffers.size(); ++i) {
    infos[i] = {buffers[i]->handle(), 0, std::min(buffers[i]->size(), max_range)};
    writes[i] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    writes[i].dstSet = set;
    writes[i].dstBinding = i;
    writes[i].descriptorCount = 1;
    writes[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    writes[i].pBufferInfo = &infos[i];
  }
  dispatchOf(context).vkUpdateDescriptorSets(
      context.device(), static_cast<std::uint32_t>(writes.size()), writes.data(), 0, nullptr);
}

}  // namespace

DescriptorSet DescriptorSet::create(Context& context, const ComputePipeline& pipeline,
                                    const std::vector<const Buffer*>& buffers) {
  requireBuffers(context, pipeline, buffers);
  // Filled step by step; if a step throws, ~DescriptorSet releases what was made.
  DescriptorSet d;
  d.context_ = &context;
  noteCreated(context);
  d.pool_ = createPool(context, pipeline.storageBufferCount());
  const VkDescriptorSetLayout layout = pipeline.setLayout();
  VkDescriptorSetAllocateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  info.descriptorPool = d.pool_;
  info.descriptorSetCount = 1;
  info.pSetLayouts = &layout;
  checkFor(dispatchOf(context).vkAllocateDescriptorSets(context.device(), &info, &d.set_),
           "vkAllocateDescriptorSets", "descriptor set for shader '" + pipeline.name() + "'");
  writeBindings(context, d.set_, buffers);
  return d;
}

DescriptorSet::~DescriptorSet() { release(); }

DescriptorSet::DescriptorSet(DescriptorSet&& other) noexcept { *this = std::move(other); }

DescriptorSet& DescriptorSet::operator=(DescriptorSet&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
    set_ = std::exchange(other.set_, VK_NULL_HANDLE);
  }
  return *this;
}

void DescriptorSet::release() {
  if (context_ == nullptr) return;
  // The set goes with its pool.
  if (pool_ != VK_NULL_HANDLE) {
    dispatchOf(*context_).vkDestroyDescriptorPool(context_->device(), pool_, nullptr);
  }
  noteDestroyed(*context_);
  context_ = nullptr;
  pool_ = VK_NULL_HANDLE;
  set_ = VK_NULL_HANDLE;
}

}  // namespace strata::vk

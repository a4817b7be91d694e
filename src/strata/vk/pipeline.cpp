// ComputePipeline: one embedded shader, N storage buffers at set 0, push constants, spec constants.
#include <utility>

#include "strata/core/error.h"
#include "strata/core/shader_registry.h"
#include "strata/vk/internal/context_impl.h"
#include "strata/vk/internal/result.h"

namespace strata::vk {
namespace {

std::uint32_t maxPushConstantBytes(const Context& context) {
  VkPhysicalDeviceProperties properties{};
  dispatchOf(context).vkGetPhysicalDeviceProperties(context.physicalDevice(), &properties);
  return properties.limits.maxPushConstantsSize;
}

void requirePushConstantSize(const Context& context, const std::string& subject,
                             std::uint32_t bytes) {
  const std::uint32_t max_bytes = maxPushConstantBytes(context);
  if (bytes % 4 != 0 || bytes > max_bytes) {
    throw DeviceError(subject + ": " + std::to_string(bytes) +
                      " bytes of push constants; need a multiple of 4 and at most " +
                      std::to_string(max_bytes) + " (maxPushConstantsSize of this device)");
  }
}

VkShaderModule createModule(const Context& context, const shaders::ShaderEntry& spirv,
                            const std::string& subject) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spirv.word_count * sizeof(std::uint32_t);
  info.pCode = spirv.words;
  VkShaderModule module = VK_NULL_HANDLE;
  checkFor(dispatchOf(context).vkCreateShaderModule(context.device(), &info, nullptr, &module),
           "vkCreateShaderModule", subject);
  return module;
}

VkDescriptorSetLayout createSetLayout(const Context& context, std::uint32_t storage_buffer_count,
                                      const std::string& subject) {
  std::vector<VkDescriptorSetLayoutBinding> bindings(storage_buffer_count);
  for (std::uint32_t i = 0; i < storage_buffer_count; ++i) {
    bindings[i].binding = i;
    bindings[i].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    bindings[i].descriptorCount = 1;
    bindings[i].stageFlags = VK_SHADER_STAGE_COMPUTE_BIT;
  }
  VkDescriptorSetLayoutCreateInfo info{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  info.bindingCount = storage_buffer_count;
  info.pBindings = bindings.data();
  VkDescriptorSetLayout layout = VK_NULL_HANDLE;
  checkFor(
      dispatchOf(context).vkCreateDescriptorSetLayout(context.device(), &info, nullptr, &layout),
      "vkCreateDescriptorSetLayout", subject);
  return layout;
}

VkPipelineLayout createPipelineLayout(const Context& context, VkDescriptorSetLayout set_layout,
                                      std::uint32_t push_constant_bytes,
                                      const std::string& subject) {
  const VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_constant_bytes};
  VkPipelineLayoutCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  info.setLayoutCount = 1;
  info.pSetLayouts = &set_layout;
  info.pushConstantRangeCount = push_constant_bytes > 0 ? 1 : 0;  // a range may not be empty
  info.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  checkFor(dispatchOf(context).vkCreatePipelineLayout(context.device(), &info, nullptr, &layout),
           "vkCreatePipelineLayout", subject);
  return layout;
}

VkPipeline createPipeline(const Context& context, VkShaderModule module, VkPipelineLayout layout,
                          const std::vector<std::uint32_t>& specialization,
                          const std::string& subject) {
  std::vector<VkSpecializationMapEntry> entries(specialization.size());
  for (std::uint32_t i = 0; i < entries.size(); ++i) {
    entries[i] = {i, i * static_cast<std::uint32_t>(sizeof(std::uint32_t)), sizeof(std::uint32_t)};
  }
  VkSpecializationInfo spec{};
  spec.mapEntryCount = static_cast<std::uint32_t>(entries.size());
  spec.pMapEntries = entries.data();
  spec.dataSize = specialization.size() * sizeof(std::uint32_t);
  spec.pData = specialization.data();
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = specialization.empty() ? nullptr : &spec;
  info.layout = layout;
  VkPipeline pipeline = VK_NULL_HANDLE;
  checkFor(dispatchOf(context).vkCreateComputePipelines(context.device(), VK_NULL_HANDLE, 1, &info,
                                                        nullptr, &pipeline),
           "vkCreateComputePipelines", subject);
  return pipeline;
}

}  // namespace

ComputePipeline ComputePipeline::create(Context& context, const std::string& shader_name,
                                        std::uint32_t storage_buffer_count,
                                        std::uint32_t push_constant_bytes,
                                        const std::vector<std::uint32_t>& specialization) {
  const std::string subject = "compute pipeline of shader '" + shader_name + "'";
  requirePushConstantSize(context, subject, push_constant_bytes);
  const shaders::ShaderEntry& spirv = shaders::spirv(shader_name);  // throws naming the shader
  // Filled step by step; if a step throws, ~ComputePipeline releases what was made.
  ComputePipeline p;
  p.context_ = &context;
  noteCreated(context);
  p.storage_buffer_count_ = storage_buffer_count;
  p.push_constant_bytes_ = push_constant_bytes;
  p.name_ = shader_name;
  p.module_ = createModule(context, spirv, subject);
  p.set_layout_ = createSetLayout(context, storage_buffer_count, subject);
  p.layout_ = createPipelineLayout(context, p.set_layout_, push_constant_bytes, subject);
  p.pipeline_ = createPipeline(context, p.module_, p.layout_, specialization, subject);
  const Context::Impl& impl = ContextAccess::impl(context);
  impl.setDebugName(VK_OBJECT_TYPE_PIPELINE, reinterpret_cast<std::uint64_t>(p.pipeline_),
                    shader_name);
  impl.setDebugName(VK_OBJECT_TYPE_SHADER_MODULE, reinterpret_cast<std::uint64_t>(p.module_),
                    shader_name);
  return p;
}

ComputePipeline::~ComputePipeline() { release(); }

ComputePipeline::ComputePipeline(ComputePipeline&& other) noexcept { *this = std::move(other); }

ComputePipeline& ComputePipeline::operator=(ComputePipeline&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    pipeline_ = std::exchange(other.pipeline_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
    set_layout_ = std::exchange(other.set_layout_, VK_NULL_HANDLE);
    module_ = std::exchange(other.module_, VK_NULL_HANDLE);
    storage_buffer_count_ = std::exchange(other.storage_buffer_count_, 0);
    push_constant_bytes_ = std::exchange(other.push_constant_bytes_, 0);
    name_ = std::move(other.name_);
  }
  return *this;
}

void ComputePipeline::release() {
  if (context_ == nullptr) return;
  const Dispatch& vk = dispatchOf(*context_);
  const VkDevice device = context_->device();
  if (pipeline_ != VK_NULL_HANDLE) vk.vkDestroyPipeline(device, pipeline_, nullptr);
  if (layout_ != VK_NULL_HANDLE) vk.vkDestroyPipelineLayout(device, layout_, nullptr);
  if (set_layout_ != VK_NULL_HANDLE) vk.vkDestroyDescriptorSetLayout(device, set_layout_, nullptr);
  if (module_ != VK_NULL_HANDLE) vk.vkDestroyShaderModule(device, module_, nullptr);
  noteDestroyed(*context_);
  context_ = nullptr;
  pipeline_ = VK_NULL_HANDLE;
  layout_ = VK_NULL_HANDLE;
  set_layout_ = VK_NULL_HANDLE;
  module_ = VK_NULL_HANDLE;
  name_.clear();
}

}  // namespace strata::vk

// Buffer: one VkBuffer with its own memory, persistently mapped when host-visible.
#include <algorithm>
#include <atomic>
#include <cstdio>
#include <utility>

#include "strata/core/error.h"
#include "strata/vk/fault_injection.h"
#include "strata/vk/internal/context_impl.h"
#include "strata/vk/internal/result.h"

namespace strata::vk {
namespace {

constexpr VkBufferUsageFlags kBufferUsage =
    VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
    VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
    VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;

// Identities of buffers, never reused (VkBuffer handles are), for caches keyed on buffers.
std::atomic<std::uint64_t> next_buffer_id{1};

// Memory that the host reads and writes at full speed and the device uses directly (lavapipe,
// integrated GPUs): device-local buffers there skip the staging copy.
constexpr VkMemoryPropertyFlags kUnifiedMemory =
    VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT | VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
    VK_MEMORY_PROPERTY_HOST_COHERENT_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT;

struct MemoryWish {
  VkMemoryPropertyFlags required;
  VkMemoryPropertyFlags preferred;
  const char* description;  // for error messages
};

MemoryWish memoryWish(MemoryUsage usage) {
  constexpr VkMemoryPropertyFlags kHostCoherent =
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  switch (usage) {
    case MemoryUsage::kDeviceLocal:
      return {0, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "device-local memory"};
    case MemoryUsage::kHostUpload:
      return {kHostCoherent, 0, "host-visible upload memory"};
    case MemoryUsage::kHostReadback:
      return {kHostCoherent, VK_MEMORY_PROPERTY_HOST_CACHED_BIT, "host-visible readback memory"};
  }
  return {0, 0, "memory"};
}

std::string mib(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return text;
}

void requireAllocatable(const Context& context, VkDeviceSize size_bytes, const std::string& name) {
  if (size_bytes == 0) {
    throw DeviceError("buffer '" + name + "': size 0; a Vulkan buffer needs at least 1 byte");
  }
  const std::uint64_t max_bytes = context.limits().max_memory_allocation_bytes;
  if (max_bytes != 0 && size_bytes > max_bytes) {
    throw DeviceError("buffer '" + name + "' of " + mib(size_bytes) + " (" +
                      std::to_string(size_bytes) +
                      " bytes) exceeds the largest single allocation "
                      "of device '" +
                      context.deviceName() + "' (" + mib(max_bytes) +
                      ", maxMemoryAllocationSize); split it into several buffers");
  }
}

void throwAllocationFailure(const Context& context, VkResult result, const std::string& name,
                            VkDeviceSize size_bytes, const char* memory_description) {
  throw DeviceError("could not allocate buffer '" + name + "' of " + mib(size_bytes) + " in " +
                    memory_description + " of device '" + context.deviceName() + "' (" +
                    mib(context.allocatedBytes()) +
                    " already allocated by Strata): " + resultName(result) +
                    "; reduce the map size or pick a device with more "
                    "memory (--device)");
}

void noteAllocated(Context::Impl& impl, std::uint64_t bytes) {
  const std::uint64_t now = impl.allocated_bytes.fetch_add(bytes) + bytes;
  std::uint64_t peak = impl.peak_allocated_bytes.load();
  while (now > peak && !impl.peak_allocated_bytes.compare_exchange_weak(peak, now)) {
  }
}

VkBuffer createHandle(const Context::Impl& impl, VkDeviceSize size_bytes, const std::string& name) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size_bytes;
  info.usage = kBufferUsage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer handle = VK_NULL_HANDLE;
  checkFor(impl.vk.vkCreateBuffer(impl.device, &info, nullptr, &handle), "vkCreateBuffer",
           "buffer '" + name + "' (" + mib(size_bytes) + ")");
  return handle;
}

// Allocates memory for `handle` into `memory` (set as soon as it exists, for cleanup) and binds
// it; returns the memory type index.
std::uint32_t allocateAndBind(Context& context, VkBuffer handle, VkDeviceSize size_bytes,
                              MemoryUsage usage, const std::string& name, VkDeviceMemory& memory) {
  Context::Impl& impl = ContextAccess::impl(context);
  VkMemoryRequirements requirements{};
  impl.vk.vkGetBufferMemoryRequirements(impl.device, handle, &requirements);
  const MemoryWish wish = memoryWish(usage);
  const std::uint32_t type_index =
      context.findMemoryType(requirements.memoryTypeBits, wish.required, wish.preferred);
  VkMemoryAllocateFlagsInfo flags{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;  // needed for deviceAddress()
  VkMemoryAllocateInfo allocate{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &flags};
  allocate.allocationSize = requirements.size;
  allocate.memoryTypeIndex = type_index;
  // Tests may stand in for a full device here (fault_injection.h); the error path is the same.
  const VkResult allocated =
      FaultInjection::failAllocation(name)
          ? VK_ERROR_OUT_OF_DEVICE_MEMORY
          : impl.vk.vkAllocateMemory(impl.device, &allocate, nullptr, &memory);
  if (allocated != VK_SUCCESS) {
    throwAllocationFailure(context, allocated, name, size_bytes, wish.description);
  }
  noteAllocated(impl, size_bytes);
  checkFor(impl.vk.vkBindBufferMemory(impl.device, handle, memory, 0), "vkBindBufferMemory",
           "buffer '" + name + "'");
  return type_index;
}

}  // namespace

Buffer Buffer::create(Context& context, VkDeviceSize size_bytes, MemoryUsage usage,
                      const std::string& debug_name) {
  requireAllocatable(context, size_bytes, debug_name);
  Context::Impl& impl = *context.impl_;
  // Filled step by step; if a step throws, ~Buffer releases what was made.
  Buffer buffer;
  buffer.context_ = &context;
  noteCreated(context);
  buffer.size_bytes_ = size_bytes;
  buffer.name_ = debug_name;
  buffer.id_ = next_buffer_id.fetch_add(1);
  buffer.buffer_ = createHandle(impl, size_bytes, debug_name);
  const std::uint32_t type_index =
      allocateAndBind(context, buffer.buffer_, size_bytes, usage, debug_name, buffer.memory_);
  const VkMemoryPropertyFlags properties =
      impl.memory_properties.memoryTypes[type_index].propertyFlags;
  const bool host_usage = usage != MemoryUsage::kDeviceLocal;
  const bool unified = (properties & kUnifiedMemory) == kUnifiedMemory && !impl.staged_memory;
  if (host_usage || unified) {
    void* pointer = nullptr;
    checkFor(impl.vk.vkMapMemory(impl.device, buffer.memory_, 0, VK_WHOLE_SIZE, 0, &pointer),
             "vkMapMemory", "buffer '" + debug_name + "'");
    (host_usage ? buffer.mapped_ : buffer.host_view_) = pointer;
  }
  VkBufferDeviceAddressInfo address{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  address.buffer = buffer.buffer_;
  buffer.address_ = impl.vk.vkGetBufferDeviceAddress(impl.device, &address);
  impl.setDebugName(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<std::uint64_t>(buffer.buffer_),
                    debug_name);
  impl.setDebugName(VK_OBJECT_TYPE_DEVICE_MEMORY, reinterpret_cast<std::uint64_t>(buffer.memory_),
                    debug_name);
  return buffer;
}

Buffer::~Buffer() { release(); }

Buffer::Buffer(Buffer&& other) noexcept
    : context_(std::exchange(other.context_, nullptr)),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      size_bytes_(std::exchange(other.size_bytes_, 0)),
      address_(std::exchange(other.address_, 0)),
      mapped_(std::exchange(other.mapped_, nullptr)),
      host_view_(std::exchange(other.host_view_, nullptr)),
      id_(std::exchange(other.id_, 0)),
      name_(std::move(other.name_)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_bytes_ = std::exchange(other.size_bytes_, 0);
    address_ = std::exchange(other.address_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
    host_view_ = std::exchange(other.host_view_, nullptr);
    id_ = std::exchange(other.id_, 0);
    name_ = std::move(other.name_);
  }
  return *this;
}

void Buffer::release() {
  if (context_ == nullptr) return;
  Context::Impl& impl = *context_->impl_;
  if (buffer_ != VK_NULL_HANDLE) impl.vk.vkDestroyBuffer(impl.device, buffer_, nullptr);
  if (memory_ != VK_NULL_HANDLE) {
    impl.vk.vkFreeMemory(impl.device, memory_, nullptr);  // also unmaps
    impl.allocated_bytes.fetch_sub(size_bytes_);
  }
  noteDestroyed(*context_);
  context_ = nullptr;
  buffer_ = VK_NULL_HANDLE;
  memory_ = VK_NULL_HANDLE;
  size_bytes_ = 0;
  address_ = 0;
  mapped_ = nullptr;
  host_view_ = nullptr;
  name_.clear();
}

}  // namespace strata::vk

#pragma once
// Private: what a Context holds, and the access the other wrappers need to it.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include "strata/vk/loader.h"
#include "strata/vk/vk.h"

namespace strata::vk {

struct Context::Impl {
  Impl() = default;
  Impl(const Impl&) = delete;
  Impl& operator=(const Impl&) = delete;
  /// Waits for the device, then destroys the pool, device, messenger and instance (each if made),
  /// so a Context that failed half-way through create() cleans up too.
  ~Impl();

  /// Names a Vulkan object for validation messages and debuggers (no-op without debug utils).
  void setDebugName(VkObjectType type, std::uint64_t handle, const std::string& name) const;

  Dispatch vk;
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  VkCommandPool command_pool = VK_NULL_HANDLE;

  std::string device_name;
  VkPhysicalDeviceType device_type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  std::string driver;  // "llvmpipe Mesa 22.3.6 (LLVM 15.0.6)"
  std::uint32_t api_version = 0;
  DeviceLimits limits;
  VkPhysicalDeviceMemoryProperties memory_properties{};
  bool validation = false;
  bool staged_memory = false;  // ContextOptions::staged_memory

  std::atomic<std::uint64_t> allocated_bytes{0};
  std::atomic<std::uint64_t> peak_allocated_bytes{0};
  // Wrappers alive on this context; ~Impl warns when some outlive it (a use-after-free to come).
  std::atomic<std::int64_t> live_objects{0};
  // Persistent staging buffers of upload()/download() where memory cannot be mapped (created at
  // first use, grown to the largest chunk asked for; released first by ~Impl).
  std::mutex staging_mutex;
  std::unique_ptr<Buffer> staging_upload;
  std::unique_ptr<Buffer> staging_download;
  std::unique_ptr<CommandBuffer> staging_commands;
};

/// The wrappers' way into a Context (friend of Context).
struct ContextAccess {
  static Context::Impl& impl(const Context& context) { return *context.impl_; }
};

inline const Dispatch& dispatchOf(const Context& context) {
  return ContextAccess::impl(context).vk;
}

/// Call after a wrapper's handles are made / before they are destroyed.
inline void noteCreated(const Context& context) { ++ContextAccess::impl(context).live_objects; }
inline void noteDestroyed(const Context& context) { --ContextAccess::impl(context).live_objects; }

}  // namespace strata::vk

// Context: instance, chosen device, one compute queue and the command pool.
#include <cstdlib>
#include <iostream>
#include <mutex>
#include <set>
#include <sstream>

#include "strata/core/error.h"
#include "strata/vk/internal/context_impl.h"
#include "strata/vk/internal/device_features.h"
#include "strata/vk/internal/device_pick.h"
#include "strata/vk/internal/instance.h"
#include "strata/vk/internal/result.h"
#include "strata/vk/internal/validation.h"

namespace strata::vk {
namespace {

// STRATA_DEVICE_MEMORY: "staged" forces the staging path, "mapped" (or unset) allows mapping
// unified memory; anything else is refused so that a typo does not silently test the wrong path.
bool stagedMemoryRequested(const ContextOptions& options) {
  if (options.staged_memory) return true;
  const char* env = std::getenv("STRATA_DEVICE_MEMORY");
  if (env == nullptr || *env == '\0' || std::string(env) == "mapped") return false;
  if (std::string(env) == "staged") return true;
  throw Error(std::string("STRATA_DEVICE_MEMORY='") + env +
              "' is not understood; use 'staged' (never map device-local memory) or 'mapped'");
}

constexpr double kBytesPerMiB = 1024.0 * 1024.0;

std::string hex(std::uint32_t value) {
  std::ostringstream text;
  text << "0x" << std::hex << value;
  return text.str();
}

std::string resolveSelector(const ContextOptions& options) {
  if (!options.device_selector.empty()) return options.device_selector;
  const char* env = std::getenv("STRATA_DEVICE");
  return env != nullptr ? std::string(env) : std::string();
}

void createDevice(Context::Impl& impl, const DeviceCandidate& chosen) {
  impl.physical_device = chosen.handle;
  impl.device_name = chosen.info.name;
  impl.device_type = chosen.info.type;
  impl.queue_family = computeQueueFamily(impl.vk, chosen.handle).value();  // checked by pick

  FeatureChain supported;
  querySupportedFeatures(impl.vk, chosen.handle, supported);
  FeatureChain enabled;
  const std::vector<const char*> extensions = selectFeatures(supported, enabled);

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = impl.queue_family;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &enabled.core};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  checkFor(impl.vk.vkCreateDevice(chosen.handle, &info, nullptr, &impl.device), "vkCreateDevice",
           "Vulkan device '" + impl.device_name + "'");
  loadDeviceFunctions(impl.vk, impl.device);
  impl.vk.vkGetDeviceQueue(impl.device, impl.queue_family, 0, &impl.queue);
  impl.limits = queryLimits(impl.vk, chosen.handle, impl.queue_family, enabled);
  impl.vk.vkGetPhysicalDeviceMemoryProperties(chosen.handle, &impl.memory_properties);
}

void createCommandPool(Context::Impl& impl) {
  VkCommandPoolCreateInfo info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  // Each CommandBuffer is re-recorded after its submit, so buffers reset individually.
  info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  info.queueFamilyIndex = impl.queue_family;
  check(impl.vk.vkCreateCommandPool(impl.device, &info, nullptr, &impl.command_pool),
        "vkCreateCommandPool");
}

void readDriverInfo(Context::Impl& impl) {
  VkPhysicalDeviceVulkan12Properties v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &v12};
  impl.vk.vkGetPhysicalDeviceProperties2(impl.physical_device, &properties);
  impl.driver = std::string(v12.driverName) + " " + v12.driverInfo;
  impl.api_version = properties.properties.apiVersion;
}

// Once per device name per process: tests and tools make many contexts on the same device.
void logDeviceOnce(const Context& context) {
  static std::mutex mutex;
  static std::set<std::string> logged;
  std::lock_guard<std::mutex> lock(mutex);
  if (!logged.insert(context.deviceName()).second) return;
  std::cerr << "strata: Vulkan device: " << context.describe() << std::endl;
}

}  // namespace

Context::Impl::~Impl() {
  staging_commands.reset();
  staging_upload.reset();
  staging_download.reset();
  if (live_objects.load() != 0) {
    std::cerr << "strata: warning: Vulkan context destroyed while " << live_objects.load()
              << " object(s) made from it are alive; destroy buffers, pipelines and command "
                 "buffers before their Context"
              << std::endl;
  }
  if (device != VK_NULL_HANDLE) {
    vk.vkDeviceWaitIdle(device);  // nothing useful to do on failure while tearing down
    if (command_pool != VK_NULL_HANDLE) vk.vkDestroyCommandPool(device, command_pool, nullptr);
    vk.vkDestroyDevice(device, nullptr);
  }
  if (messenger != VK_NULL_HANDLE) vk.vkDestroyDebugUtilsMessengerEXT(instance, messenger, nullptr);
  if (instance != VK_NULL_HANDLE) vk.vkDestroyInstance(instance, nullptr);
}

void Context::Impl::setDebugName(VkObjectType type, std::uint64_t handle,
                                 const std::string& name) const {
  if (vk.vkSetDebugUtilsObjectNameEXT == nullptr || handle == 0) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  vk.vkSetDebugUtilsObjectNameEXT(device, &info);  // a name is a debugging aid: ignore failure
}

Context::Context(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Context::~Context() = default;

std::unique_ptr<Context> Context::create(const ContextOptions& options) {
  // Built step by step inside Impl, whose destructor undoes whatever was made if a step throws.
  auto impl = std::make_unique<Impl>();
  impl->validation = validationRequested(options);
  impl->staged_memory = stagedMemoryRequested(options);
  impl->vk = globalDispatch();
  bool debug_utils = false;
  impl->instance = createInstance(impl->vk, impl->validation, debug_utils);
  if (impl->validation) impl->messenger = createMessenger(impl->vk, impl->instance);
  const std::vector<DeviceCandidate> devices = listCandidates(impl->vk, impl->instance);
  createDevice(*impl, pickDevice(impl->vk, devices, resolveSelector(options)));
  createCommandPool(*impl);
  readDriverInfo(*impl);
  std::unique_ptr<Context> context(new Context(std::move(impl)));
  if (options.log_device) logDeviceOnce(*context);
  return context;
}

std::vector<PhysicalDeviceInfo> Context::listDevices() {
  Impl scratch;  // instance only, destroyed on return
  scratch.vk = globalDispatch();
  bool debug_utils = false;
  scratch.instance = createInstance(scratch.vk, /*validation=*/false, debug_utils);
  std::vector<PhysicalDeviceInfo> infos;
  for (const DeviceCandidate& d : listCandidates(scratch.vk, scratch.instance)) {
    infos.push_back(d.info);
  }
  return infos;
}

VkInstance Context::instance() const { return impl_->instance; }
VkPhysicalDevice Context::physicalDevice() const { return impl_->physical_device; }
VkDevice Context::device() const { return impl_->device; }
VkQueue Context::queue() const { return impl_->queue; }
std::uint32_t Context::queueFamily() const { return impl_->queue_family; }
VkCommandPool Context::commandPool() const { return impl_->command_pool; }
const std::string& Context::deviceName() const { return impl_->device_name; }
VkPhysicalDeviceType Context::deviceType() const { return impl_->device_type; }
const DeviceLimits& Context::limits() const { return impl_->limits; }
bool Context::validationEnabled() const { return impl_->validation; }
bool Context::stagedMemory() const { return impl_->staged_memory; }
std::uint64_t Context::allocatedBytes() const { return impl_->allocated_bytes.load(); }
std::uint64_t Context::peakAllocatedBytes() const { return impl_->peak_allocated_bytes.load(); }

std::string Context::describe() const {
  const DeviceLimits& l = impl_->limits;
  std::ostringstream s;
  s << impl_->device_name << " (" << deviceTypeName(impl_->device_type) << "), driver "
    << impl_->driver << ", Vulkan " << VK_API_VERSION_MAJOR(impl_->api_version) << "."
    << VK_API_VERSION_MINOR(impl_->api_version) << "." << VK_API_VERSION_PATCH(impl_->api_version)
    << ", storage buffer range " << l.max_storage_buffer_range_bytes / kBytesPerMiB << " MiB"
    << ", max allocation " << l.max_memory_allocation_bytes / kBytesPerMiB << " MiB"
    << ", device-local heap " << l.device_local_heap_bytes / kBytesPerMiB << " MiB"
    << " (budget " << (l.device_local_budget_bytes > 0
                           ? std::to_string(l.device_local_budget_bytes / kBytesPerMiB) + " MiB"
                           : std::string("not reported")) << ")"
    << ", workgroup invocations " << l.max_workgroup_invocations << ", shared memory "
    << l.max_shared_memory_bytes / 1024 << " KiB, subgroup " << l.subgroup_size
    << ", timestamp period " << l.timestamp_period_ns << " ns (" << l.timestamp_valid_bits
    << " valid bits), float32 atomics: add " << (l.float32_atomic_add ? "yes" : "no")
    << ", min/max " << (l.float32_atomic_min_max ? "yes" : "no") << ", validation "
    << (impl_->validation ? "on" : "off") << ", memory "
    << (impl_->staged_memory ? "staged" : "mapped where unified");
  return s.str();
}

std::uint32_t Context::findMemoryType(std::uint32_t type_bits, VkMemoryPropertyFlags required,
                                      VkMemoryPropertyFlags preferred) const {
  const VkPhysicalDeviceMemoryProperties& memory = impl_->memory_properties;
  // Two passes: first with the preferred flags as well, then with the required ones only.
  for (VkMemoryPropertyFlags wanted : {required | preferred, required}) {
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i) {
      const bool allowed = (type_bits & (1u << i)) != 0;
      if (allowed && (memory.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
    }
  }
  throw DeviceError("device '" + impl_->device_name + "' has no memory type with property flags " +
                    hex(required) + " among the allowed types " + hex(type_bits));
}

}  // namespace strata::vk

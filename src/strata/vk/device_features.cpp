// Device requirements (checked with a message naming what is missing) and limits.
#include "strata/vk/internal/device_features.h"

#include <algorithm>
#include <cstring>

#include "strata/vk/internal/enumerate.h"

namespace strata::vk {
namespace {

// Optional features enabled whenever present; kernels may rely on them on every device that
// meets Strata's requirements in practice (all current desktop GPUs and lavapipe).
#define STRATA_VK_OPTIONAL_CORE_FEATURES(X) X(shaderInt16)
#define STRATA_VK_OPTIONAL_V11_FEATURES(X) X(storageBuffer16BitAccess)
#define STRATA_VK_OPTIONAL_V12_FEATURES(X) \
  X(shaderInt8)                            \
  X(storageBuffer8BitAccess)               \
  X(shaderSharedInt64Atomics)              \
  X(scalarBlockLayout)

bool hasExtension(const std::vector<VkExtensionProperties>& extensions, const char* name) {
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

std::string versionString(std::uint32_t version) {
  return std::to_string(VK_API_VERSION_MAJOR(version)) + "." +
         std::to_string(VK_API_VERSION_MINOR(version));
}

std::uint64_t largestDeviceLocalHeapBytes(const VkPhysicalDeviceMemoryProperties& memory) {
  std::uint64_t largest = 0;
  for (std::uint32_t i = 0; i < memory.memoryHeapCount; ++i) {
    if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) {
      largest = std::max<std::uint64_t>(largest, memory.memoryHeaps[i].size);
    }
  }
  return largest;
}

/// What the driver says this process may still allocate in the largest device-local heap
/// (VK_EXT_memory_budget: budget minus usage); 0 where the device does not report it.
std::uint64_t deviceLocalBudgetBytes(const Dispatch& vk, VkPhysicalDevice device) {
  VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
  VkPhysicalDeviceMemoryProperties2 memory{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2,
                                           &budget};
  vk.vkGetPhysicalDeviceMemoryProperties2(device, &memory);
  const VkPhysicalDeviceMemoryProperties& m = memory.memoryProperties;
  std::uint64_t largest = 0;
  std::uint64_t available = 0;
  for (std::uint32_t i = 0; i < m.memoryHeapCount; ++i) {
    if ((m.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT) == 0) continue;
    if (m.memoryHeaps[i].size <= largest) continue;
    largest = m.memoryHeaps[i].size;
    available = budget.heapBudget[i] > budget.heapUsage[i]
                    ? budget.heapBudget[i] - budget.heapUsage[i]
                    : 0;
  }
  return available;
}

}  // namespace

void FeatureChain::link() {
  core.pNext = &v11;
  v11.pNext = &v12;
  void** tail = &v12.pNext;
  *tail = nullptr;
  if (has_atomic_float) {
    *tail = &atomic_float;
    tail = &atomic_float.pNext;
    *tail = nullptr;
  }
  if (has_atomic_float2) {
    *tail = &atomic_float2;
    atomic_float2.pNext = nullptr;
  }
}

void querySupportedFeatures(const Dispatch& vk, VkPhysicalDevice device, FeatureChain& supported) {
  const auto extensions = enumerateChecked<VkExtensionProperties>(
      "vkEnumerateDeviceExtensionProperties",
      [&](std::uint32_t* count, VkExtensionProperties* data) {
        return vk.vkEnumerateDeviceExtensionProperties(device, nullptr, count, data);
      });
  supported.has_atomic_float = hasExtension(extensions, VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
  supported.has_atomic_float2 =
      hasExtension(extensions, VK_EXT_SHADER_ATOMIC_FLOAT_2_EXTENSION_NAME);
  supported.has_memory_budget = hasExtension(extensions, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
  supported.link();
  vk.vkGetPhysicalDeviceFeatures2(device, &supported.core);
}

std::vector<const char*> selectFeatures(const FeatureChain& supported, FeatureChain& enabled) {
  // Required (missingRequirements() has checked them).
  enabled.core.features.shaderInt64 = VK_TRUE;
  enabled.v12.shaderBufferInt64Atomics = VK_TRUE;
  enabled.v12.bufferDeviceAddress = VK_TRUE;
#define STRATA_VK_COPY_CORE(f) enabled.core.features.f = supported.core.features.f;
#define STRATA_VK_COPY_V11(f) enabled.v11.f = supported.v11.f;
#define STRATA_VK_COPY_V12(f) enabled.v12.f = supported.v12.f;
  STRATA_VK_OPTIONAL_CORE_FEATURES(STRATA_VK_COPY_CORE)
  STRATA_VK_OPTIONAL_V11_FEATURES(STRATA_VK_COPY_V11)
  STRATA_VK_OPTIONAL_V12_FEATURES(STRATA_VK_COPY_V12)
#undef STRATA_VK_COPY_CORE
#undef STRATA_VK_COPY_V11
#undef STRATA_VK_COPY_V12
  std::vector<const char*> extensions;
  if (supported.has_atomic_float && supported.atomic_float.shaderBufferFloat32AtomicAdd) {
    enabled.has_atomic_float = true;
    enabled.atomic_float.shaderBufferFloat32Atomics =
        supported.atomic_float.shaderBufferFloat32Atomics;
    enabled.atomic_float.shaderBufferFloat32AtomicAdd = VK_TRUE;
    extensions.push_back(VK_EXT_SHADER_ATOMIC_FLOAT_EXTENSION_NAME);
  }
  if (supported.has_atomic_float2 && supported.atomic_float2.shaderBufferFloat32AtomicMinMax) {
    enabled.has_atomic_float2 = true;
    enabled.atomic_float2.shaderBufferFloat32AtomicMinMax = VK_TRUE;
    extensions.push_back(VK_EXT_SHADER_ATOMIC_FLOAT_2_EXTENSION_NAME);
  }
  if (supported.has_memory_budget) {
    enabled.has_memory_budget = true;
    extensions.push_back(VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
  }
  enabled.link();
  return extensions;
}

std::optional<std::uint32_t> computeQueueFamily(const Dispatch& vk, VkPhysicalDevice device) {
  const auto families = enumerateAll<VkQueueFamilyProperties>(
      [&](std::uint32_t* count, VkQueueFamilyProperties* data) {
        vk.vkGetPhysicalDeviceQueueFamilyProperties(device, count, data);
      });
  for (std::uint32_t i = 0; i < families.size(); ++i) {
    if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && families[i].timestampValidBits > 0) {
      return i;
    }
  }
  return std::nullopt;
}

std::string missingRequirements(const Dispatch& vk, VkPhysicalDevice device) {
  VkPhysicalDeviceProperties properties{};
  vk.vkGetPhysicalDeviceProperties(device, &properties);
  if (properties.apiVersion < VK_API_VERSION_1_2) {
    // The feature query below needs 1.2 structs, so stop here.
    return "Vulkan 1.2 (device has " + versionString(properties.apiVersion) + ")";
  }
  FeatureChain supported;
  querySupportedFeatures(vk, device, supported);
  std::vector<std::string> missing;
  if (!supported.core.features.shaderInt64) missing.push_back("shaderInt64");
  if (!supported.v12.shaderBufferInt64Atomics) missing.push_back("shaderBufferInt64Atomics");
  if (!supported.v12.bufferDeviceAddress) missing.push_back("bufferDeviceAddress");
  if (!computeQueueFamily(vk, device)) {
    missing.push_back("a compute queue with timestamp queries (timestampValidBits > 0)");
  }
  // estimate_normals.comp reduces runs of 4 invocations with subgroupShuffleXor / subgroupAll.
  VkPhysicalDeviceVulkan11Properties v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
  VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &v11};
  vk.vkGetPhysicalDeviceProperties2(device, &properties2);
  if ((v11.subgroupSupportedStages & VK_SHADER_STAGE_COMPUTE_BIT) == 0 ||
      (v11.subgroupSupportedOperations & VK_SUBGROUP_FEATURE_SHUFFLE_BIT) == 0 ||
      (v11.subgroupSupportedOperations & VK_SUBGROUP_FEATURE_VOTE_BIT) == 0 ||
      v11.subgroupSize < 4) {
    missing.push_back("subgroup shuffle and vote in compute shaders with subgroups of at least 4 (device: " +
                      std::to_string(v11.subgroupSize) + "-wide)");
  }
  // The largest workgroups: 8x8x8 (ESDF sweeps, meshing), 256x1x1 and 16x16x1 (see shaders/).
  const VkPhysicalDeviceLimits& limits = properties.limits;
  if (limits.maxComputeWorkGroupInvocations < kRequiredWorkgroupInvocations ||
      limits.maxComputeWorkGroupSize[0] < 256 || limits.maxComputeWorkGroupSize[1] < 16 ||
      limits.maxComputeWorkGroupSize[2] < 8) {
    missing.push_back("compute workgroups of " + std::to_string(kRequiredWorkgroupInvocations) +
                      " invocations and sizes 256x16x8 (device: " +
                      std::to_string(limits.maxComputeWorkGroupInvocations) + ", " +
                      std::to_string(limits.maxComputeWorkGroupSize[0]) + "x" +
                      std::to_string(limits.maxComputeWorkGroupSize[1]) + "x" +
                      std::to_string(limits.maxComputeWorkGroupSize[2]) + ")");
  }
  std::string joined;
  for (const std::string& item : missing) joined += (joined.empty() ? "" : ", ") + item;
  return joined;
}

DeviceLimits queryLimits(const Dispatch& vk, VkPhysicalDevice device, std::uint32_t queue_family,
                         const FeatureChain& enabled) {
  VkPhysicalDeviceVulkan11Properties v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &v11};
  vk.vkGetPhysicalDeviceProperties2(device, &properties);
  const VkPhysicalDeviceLimits& core = properties.properties.limits;
  const auto families = enumerateAll<VkQueueFamilyProperties>(
      [&](std::uint32_t* count, VkQueueFamilyProperties* data) {
        vk.vkGetPhysicalDeviceQueueFamilyProperties(device, count, data);
      });
  VkPhysicalDeviceMemoryProperties memory{};
  vk.vkGetPhysicalDeviceMemoryProperties(device, &memory);

  DeviceLimits limits;
  limits.max_storage_buffer_range_bytes = core.maxStorageBufferRange;
  limits.max_memory_allocation_bytes = v11.maxMemoryAllocationSize;
  limits.max_workgroup_invocations = core.maxComputeWorkGroupInvocations;
  limits.max_shared_memory_bytes = core.maxComputeSharedMemorySize;
  limits.subgroup_size = v11.subgroupSize;
  limits.timestamp_period_ns = core.timestampPeriod;
  limits.timestamp_valid_bits = families.at(queue_family).timestampValidBits;
  limits.device_local_heap_bytes = largestDeviceLocalHeapBytes(memory);
  limits.float32_atomic_add = enabled.has_atomic_float;
  limits.float32_atomic_min_max = enabled.has_atomic_float2;
  limits.device_local_budget_bytes =
      enabled.has_memory_budget ? deviceLocalBudgetBytes(vk, device) : 0;
  return limits;
}

}  // namespace strata::vk

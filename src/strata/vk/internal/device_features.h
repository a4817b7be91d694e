#pragma once
// Private: what Strata requires of a device, the optional features it enables, and its limits.
#include <optional>
#include <string>
#include <vector>

#include "strata/vk/loader.h"

namespace strata::vk {

/// The pNext chain of feature structs Strata queries and enables. Holds pointers into itself:
/// not copyable; call link() after filling and before handing it to Vulkan.
struct FeatureChain {
  FeatureChain() = default;
  FeatureChain(const FeatureChain&) = delete;
  FeatureChain& operator=(const FeatureChain&) = delete;
  void link();

  VkPhysicalDeviceFeatures2 core{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan11Features v11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceShaderAtomicFloatFeaturesEXT atomic_float{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_FEATURES_EXT};
  VkPhysicalDeviceShaderAtomicFloat2FeaturesEXT atomic_float2{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SHADER_ATOMIC_FLOAT_2_FEATURES_EXT};
  // Whether the extension of each optional struct is present (only then is it chained).
  bool has_atomic_float = false;
  bool has_atomic_float2 = false;
  bool has_memory_budget = false;  // VK_EXT_memory_budget (a query only, no feature struct)
};

/// The device's features. Only valid for a device with Vulkan >= 1.2.
void querySupportedFeatures(const Dispatch& vk, VkPhysicalDevice device, FeatureChain& supported);

/// Required features, plus every optional one `supported` has; returns the extensions to enable.
std::vector<const char*> selectFeatures(const FeatureChain& supported, FeatureChain& enabled);

/// A queue family with compute and timestamps, if the device has one.
std::optional<std::uint32_t> computeQueueFamily(const Dispatch& vk, VkPhysicalDevice device);

/// The largest workgroup a Strata kernel uses (8x8x8).
constexpr std::uint32_t kRequiredWorkgroupInvocations = 512;

/// "" when `device` has everything Strata requires, otherwise what it lacks, comma-separated
/// ("Vulkan 1.2 (device has 1.1), shaderBufferInt64Atomics").
std::string missingRequirements(const Dispatch& vk, VkPhysicalDevice device);

/// Limits of `device` as used through `queue_family`, and its optional features in `enabled`.
DeviceLimits queryLimits(const Dispatch& vk, VkPhysicalDevice device, std::uint32_t queue_family,
                         const FeatureChain& enabled);

}  // namespace strata::vk

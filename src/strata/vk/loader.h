#pragma once
// Private: the Vulkan loader, opened at run time, and the table of the Vulkan functions Strata
// uses.
// NOTE: nothing links libvulkan, so a binary starts (and can print a useful error) on a machine
// without Vulkan; every call goes through a Dispatch table.
#include "strata/vk/vk.h"

namespace strata::vk {

// Functions available before an instance exists.
#define STRATA_VK_GLOBAL_FUNCTIONS(X)   \
  X(vkCreateInstance)                   \
  X(vkEnumerateInstanceVersion)         \
  X(vkEnumerateInstanceLayerProperties) \
  X(vkEnumerateInstanceExtensionProperties)

// Core instance-level functions (loaded through vkGetInstanceProcAddr).
#define STRATA_VK_INSTANCE_FUNCTIONS(X)       \
  X(vkDestroyInstance)                        \
  X(vkEnumeratePhysicalDevices)               \
  X(vkGetPhysicalDeviceProperties)            \
  X(vkGetPhysicalDeviceProperties2)           \
  X(vkGetPhysicalDeviceFeatures2)             \
  X(vkGetPhysicalDeviceQueueFamilyProperties) \
  X(vkGetPhysicalDeviceMemoryProperties)      \
  X(vkGetPhysicalDeviceMemoryProperties2)     \
  X(vkEnumerateDeviceExtensionProperties)     \
  X(vkCreateDevice)                           \
  X(vkGetDeviceProcAddr)

// VK_EXT_debug_utils: null unless the extension was enabled on the instance.
#define STRATA_VK_DEBUG_UTILS_FUNCTIONS(X) \
  X(vkCreateDebugUtilsMessengerEXT)        \
  X(vkDestroyDebugUtilsMessengerEXT)       \
  X(vkSetDebugUtilsObjectNameEXT)

// Device-level functions (loaded through vkGetDeviceProcAddr: no loader trampoline per call).
#define STRATA_VK_DEVICE_FUNCTIONS(X) \
  X(vkDestroyDevice)                  \
  X(vkGetDeviceQueue)                 \
  X(vkDeviceWaitIdle)                 \
  X(vkCreateBuffer)                   \
  X(vkDestroyBuffer)                  \
  X(vkGetBufferMemoryRequirements)    \
  X(vkAllocateMemory)                 \
  X(vkFreeMemory)                     \
  X(vkBindBufferMemory)               \
  X(vkMapMemory)                      \
  X(vkGetBufferDeviceAddress)         \
  X(vkCreateShaderModule)             \
  X(vkDestroyShaderModule)            \
  X(vkCreateDescriptorSetLayout)      \
  X(vkDestroyDescriptorSetLayout)     \
  X(vkCreatePipelineLayout)           \
  X(vkDestroyPipelineLayout)          \
  X(vkCreateComputePipelines)         \
  X(vkDestroyPipeline)                \
  X(vkCreateDescriptorPool)           \
  X(vkDestroyDescriptorPool)          \
  X(vkAllocateDescriptorSets)         \
  X(vkUpdateDescriptorSets)           \
  X(vkCreateCommandPool)              \
  X(vkDestroyCommandPool)             \
  X(vkAllocateCommandBuffers)         \
  X(vkFreeCommandBuffers)             \
  X(vkBeginCommandBuffer)             \
  X(vkEndCommandBuffer)               \
  X(vkCreateFence)                    \
  X(vkDestroyFence)                   \
  X(vkResetFences)                    \
  X(vkWaitForFences)                  \
  X(vkQueueSubmit)                    \
  X(vkCreateQueryPool)                \
  X(vkDestroyQueryPool)               \
  X(vkGetQueryPoolResults)            \
  X(vkCmdBindPipeline)                \
  X(vkCmdBindDescriptorSets)          \
  X(vkCmdPushConstants)               \
  X(vkCmdDispatch)                    \
  X(vkCmdDispatchIndirect)            \
  X(vkCmdPipelineBarrier)             \
  X(vkCmdCopyBuffer)                  \
  X(vkCmdFillBuffer)                  \
  X(vkCmdResetQueryPool)              \
  X(vkCmdWriteTimestamp)

#define STRATA_VK_DECLARE_POINTER(name) PFN_##name name = nullptr;

/// Function pointers of one instance and (once created) one device.
struct Dispatch {
  PFN_vkGetInstanceProcAddr vkGetInstanceProcAddr = nullptr;
  STRATA_VK_GLOBAL_FUNCTIONS(STRATA_VK_DECLARE_POINTER)
  STRATA_VK_INSTANCE_FUNCTIONS(STRATA_VK_DECLARE_POINTER)
  STRATA_VK_DEBUG_UTILS_FUNCTIONS(STRATA_VK_DECLARE_POINTER)
  STRATA_VK_DEVICE_FUNCTIONS(STRATA_VK_DECLARE_POINTER)
};

/// The global functions of the process-wide loader (opened on first use, never closed).
/// Throws DeviceError with installation advice when libvulkan cannot be opened.
const Dispatch& globalDispatch();

/// Fills the instance-level (and, when `debug_utils`, VK_EXT_debug_utils) functions.
void loadInstanceFunctions(Dispatch& vk, VkInstance instance, bool debug_utils);

/// Fills the device-level functions.
void loadDeviceFunctions(Dispatch& vk, VkDevice device);

}  // namespace strata::vk

#pragma once
// Private: choosing the physical device (automatic ranking, or a selector by index or name).
#include <string>
#include <vector>

#include "strata/vk/loader.h"

namespace strata::vk {

struct DeviceCandidate {
  VkPhysicalDevice handle = VK_NULL_HANDLE;
  PhysicalDeviceInfo info;
};

/// Every physical device of `instance`, in the loader's order. Throws DeviceError (advising
/// mesa-vulkan-drivers) when there is none.
std::vector<DeviceCandidate> listCandidates(const Dispatch& vk, VkInstance instance);

/// "discrete GPU", "integrated GPU", "virtual GPU", "CPU", "other".
std::string deviceTypeName(VkPhysicalDeviceType type);

/// The device to use. `selector` "" ranks discrete > integrated > virtual > CPU > other among the
/// devices that meet Strata's requirements; an index or a case-insensitive name substring picks
/// that device. Throws DeviceError listing the devices when nothing matches, or naming what the
/// picked device lacks.
const DeviceCandidate& pickDevice(const Dispatch& vk, const std::vector<DeviceCandidate>& devices,
                                  const std::string& selector);

}  // namespace strata::vk

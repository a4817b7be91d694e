// Physical-device choice: the best GPU automatically, lavapipe last; overridable by selector.
#include "strata/vk/internal/device_pick.h"

#include <algorithm>
#include <cctype>

#include "strata/core/error.h"
#include "strata/vk/internal/device_features.h"
#include "strata/vk/internal/enumerate.h"

namespace strata::vk {
namespace {

// Lower is better.
int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return 3;
    default:
      return 4;
  }
}

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

bool isIndex(const std::string& selector) {
  return !selector.empty() && selector.size() < 10 &&
         std::all_of(selector.begin(), selector.end(),
                     [](unsigned char c) { return std::isdigit(c) != 0; });
}

std::string listForMessage(const std::vector<DeviceCandidate>& devices) {
  std::string text;
  for (const DeviceCandidate& d : devices) {
    text += "\n  " + std::to_string(d.info.index) + ": " + d.info.name + " (" +
            deviceTypeName(d.info.type) + ")";
  }
  return text;
}

// Devices in order of preference (stable, so ties keep the loader's order).
std::vector<const DeviceCandidate*> ranked(const std::vector<DeviceCandidate>& devices) {
  std::vector<const DeviceCandidate*> order;
  for (const DeviceCandidate& d : devices) order.push_back(&d);
  std::stable_sort(order.begin(), order.end(), [](const auto* a, const auto* b) {
    return typeRank(a->info.type) < typeRank(b->info.type);
  });
  return order;
}

const DeviceCandidate& requireSuitable(const Dispatch& vk, const DeviceCandidate& device) {
  const std::string missing = missingRequirements(vk, device.handle);
  if (!missing.empty()) {
    throw DeviceError("Vulkan device " + std::to_string(device.info.index) + " '" +
                      device.info.name + "' lacks what Strata requires: " + missing +
                      "; update the driver or pick another device (--device / STRATA_DEVICE)");
  }
  return device;
}

const DeviceCandidate& pickAutomatically(const Dispatch& vk,
                                         const std::vector<DeviceCandidate>& devices) {
  const std::vector<const DeviceCandidate*> order = ranked(devices);
  for (const DeviceCandidate* d : order) {
    if (missingRequirements(vk, d->handle).empty()) return *d;
  }
  return requireSuitable(vk, *order.front());  // throws, naming what the best device lacks
}

const DeviceCandidate* matchSelector(const std::vector<DeviceCandidate>& devices,
                                     const std::string& selector) {
  if (isIndex(selector)) {
    const unsigned long index = std::stoul(selector);
    return index < devices.size() ? &devices[index] : nullptr;
  }
  const std::string wanted = lowercase(selector);
  for (const DeviceCandidate* d : ranked(devices)) {
    if (lowercase(d->info.name).find(wanted) != std::string::npos) return d;
  }
  return nullptr;
}

}  // namespace

std::string deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU:
      return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU:
      return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU:
      return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU:
      return "CPU";
    default:
      return "other";
  }
}

std::vector<DeviceCandidate> listCandidates(const Dispatch& vk, VkInstance instance) {
  const auto handles = enumerateChecked<VkPhysicalDevice>(
      "vkEnumeratePhysicalDevices", [&](std::uint32_t* count, VkPhysicalDevice* data) {
        return vk.vkEnumeratePhysicalDevices(instance, count, data);
      });
  if (handles.empty()) {
    throw DeviceError(
        "no Vulkan device found: install a driver, e.g. mesa-vulkan-drivers (lavapipe runs the "
        "kernels on the CPU) or your GPU vendor's Vulkan driver");
  }
  std::vector<DeviceCandidate> devices;
  for (std::uint32_t i = 0; i < handles.size(); ++i) {
    VkPhysicalDeviceProperties properties{};
    vk.vkGetPhysicalDeviceProperties(handles[i], &properties);
    devices.push_back({handles[i], {i, properties.deviceName, properties.deviceType}});
  }
  return devices;
}

const DeviceCandidate& pickDevice(const Dispatch& vk, const std::vector<DeviceCandidate>& devices,
                                  const std::string& selector) {
  if (selector.empty()) return pickAutomatically(vk, devices);
  const DeviceCandidate* match = matchSelector(devices, selector);
  if (match == nullptr) {
    throw DeviceError(
        "no Vulkan device matches '" + selector +
        "' (a device index or part of its name); available devices:" + listForMessage(devices));
  }
  return requireSuitable(vk, *match);
}

}  // namespace strata::vk

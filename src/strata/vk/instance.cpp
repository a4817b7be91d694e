// Instance creation: Vulkan 1.2, optional validation layer and debug utils.
#include "strata/vk/internal/instance.h"

#include <dlfcn.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "strata/core/error.h"
#include "strata/vk/internal/enumerate.h"
#include "strata/vk/internal/validation.h"

// Whether this translation unit is built with AddressSanitizer (gcc and clang spell it apart).
#if defined(__SANITIZE_ADDRESS__)
#define STRATA_ADDRESS_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define STRATA_ADDRESS_SANITIZER 1
#endif
#endif

namespace strata::vk {
namespace {

void requireLoaderVersion(const Dispatch& vk) {
  std::uint32_t version = VK_API_VERSION_1_0;  // loaders without the call are 1.0
  if (vk.vkEnumerateInstanceVersion != nullptr) {
    check(vk.vkEnumerateInstanceVersion(&version), "vkEnumerateInstanceVersion");
  }
  if (version < VK_API_VERSION_1_2) {
    throw DeviceError(
        "the Vulkan loader supports Vulkan " + std::to_string(VK_API_VERSION_MAJOR(version)) + "." +
        std::to_string(VK_API_VERSION_MINOR(version)) + "; Strata needs 1.2: update libvulkan1");
  }
}

bool instanceExtensionAvailable(const Dispatch& vk, const char* extension, const char* layer) {
  const auto extensions = enumerateChecked<VkExtensionProperties>(
      "vkEnumerateInstanceExtensionProperties",
      [&](std::uint32_t* count, VkExtensionProperties* data) {
        return vk.vkEnumerateInstanceExtensionProperties(layer, count, data);
      });
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, extension) == 0;
  });
}

// What vkCreateInstance is given; the pNext structs must live until the call returns.
struct InstanceSetup {
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  VkDebugUtilsMessengerCreateInfoEXT messenger = messengerCreateInfo();
  VkValidationFeatureEnableEXT sync_validation =
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
};

// Sanitizer builds only: the validation layer, Mesa's lavapipe driver and its device-select layer
// keep a few allocations in their globals until the process ends, and the loader unloads them at
// vkDestroyInstance, so LeakSanitizer would report those blocks (no longer reachable from any
// mapped global) from an "unknown module" that no suppression can name. Holding the libraries
// mapped (RTLD_NODELETE) keeps such blocks reachable or nameable in scripts/sanitizers/lsan.supp,
// and our own leaks still fail. (Mesa 22.3.6-1+deb12u2's lavapipe leaks 128 bytes this way.)
void keepLibrariesMappedForLeakReports() {
#ifdef STRATA_ADDRESS_SANITIZER
  // An absent library is fine: the layer has been required already, the others are optional.
  static void* const libraries[] = {
      dlopen("libVkLayer_khronos_validation.so", RTLD_NOW | RTLD_NODELETE),
      dlopen("libvulkan_lvp.so", RTLD_NOW | RTLD_NODELETE),
      dlopen("libVkLayer_MESA_device_select.so", RTLD_NOW | RTLD_NODELETE),
  };
  (void)libraries;
#endif
}

// Layer, debug utils, and synchronization validation: it finds missing barriers between
// dispatches, the commonest compute bug, and measured on lavapipe it adds nothing noticeable
// (2000 dispatches with barriers: 0.55 s with and without).
void addValidation(const Dispatch& vk, InstanceSetup& setup) {
  requireValidationLayer(vk);
  setup.layers.push_back(kValidationLayerName);
  if (instanceExtensionAvailable(vk, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME,
                                 kValidationLayerName)) {
    setup.extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
    setup.features.enabledValidationFeatureCount = 1;
    setup.features.pEnabledValidationFeatures = &setup.sync_validation;
    setup.messenger.pNext = &setup.features;
  }
}

}  // namespace

VkInstance createInstance(Dispatch& vk, bool validation, bool& debug_utils) {
  keepLibrariesMappedForLeakReports();
  requireLoaderVersion(vk);
  InstanceSetup setup;
  if (validation) addValidation(vk, setup);
  debug_utils = instanceExtensionAvailable(vk, VK_EXT_DEBUG_UTILS_EXTENSION_NAME, nullptr) ||
                (validation && instanceExtensionAvailable(vk, VK_EXT_DEBUG_UTILS_EXTENSION_NAME,
                                                          kValidationLayerName));
  if (validation && !debug_utils) {
    throw DeviceError(
        "validation requested but VK_EXT_debug_utils is unavailable: update "
        "libvulkan1 and vulkan-validationlayers");
  }
  if (debug_utils) setup.extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "strata";
  app.pEngineName = "strata";
  app.apiVersion = VK_API_VERSION_1_2;
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  // The messenger is chained so that vkCreateInstance/vkDestroyInstance are validated too.
  info.pNext = validation ? &setup.messenger : nullptr;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<std::uint32_t>(setup.layers.size());
  info.ppEnabledLayerNames = setup.layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(setup.extensions.size());
  info.ppEnabledExtensionNames = setup.extensions.data();
  VkInstance instance = VK_NULL_HANDLE;
  check(vk.vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
  try {
    loadInstanceFunctions(vk, instance, debug_utils);
  } catch (...) {
    if (vk.vkDestroyInstance != nullptr) vk.vkDestroyInstance(instance, nullptr);
    throw;
  }
  return instance;
}

VkDebugUtilsMessengerEXT createMessenger(const Dispatch& vk, VkInstance instance) {
  if (vk.vkCreateDebugUtilsMessengerEXT == nullptr) {
    throw DeviceError(
        "validation requested but the loader provides no "
        "vkCreateDebugUtilsMessengerEXT: update libvulkan1");
  }
  const VkDebugUtilsMessengerCreateInfoEXT info = messengerCreateInfo();
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  check(vk.vkCreateDebugUtilsMessengerEXT(instance, &info, nullptr, &messenger),
        "vkCreateDebugUtilsMessengerEXT");
  return messenger;
}

}  // namespace strata::vk

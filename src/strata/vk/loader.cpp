// Opens libvulkan at run time and fills the dispatch table.
#include "strata/vk/loader.h"

#include <dlfcn.h>

#include <string>

#include "strata/core/error.h"

namespace strata::vk {
namespace {

constexpr const char* kLoaderMissing =
    "Vulkan loader libvulkan.so.1 not found: install libvulkan1 (Debian) and a driver such as "
    "mesa-vulkan-drivers";

PFN_vkGetInstanceProcAddr openLoader() {
  // NOTE: the handle is never closed; layers and drivers keep pointers into it until exit.
  void* library = dlopen("libvulkan.so.1", RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) library = dlopen("libvulkan.so", RTLD_NOW | RTLD_LOCAL);
  if (library == nullptr) throw DeviceError(kLoaderMissing);
  auto get_proc =
      reinterpret_cast<PFN_vkGetInstanceProcAddr>(dlsym(library, "vkGetInstanceProcAddr"));
  if (get_proc == nullptr) {
    throw DeviceError(std::string(kLoaderMissing) +
                      " (libvulkan was found but exports no vkGetInstanceProcAddr)");
  }
  return get_proc;
}

Dispatch loadGlobalFunctions() {
  Dispatch vk;
  vk.vkGetInstanceProcAddr = openLoader();
#define STRATA_VK_LOAD_GLOBAL(name) \
  vk.name = reinterpret_cast<PFN_##name>(vk.vkGetInstanceProcAddr(VK_NULL_HANDLE, #name));
  STRATA_VK_GLOBAL_FUNCTIONS(STRATA_VK_LOAD_GLOBAL)
#undef STRATA_VK_LOAD_GLOBAL
  // vkEnumerateInstanceVersion is absent from Vulkan 1.0 loaders; the caller treats null as 1.0.
  if (vk.vkCreateInstance == nullptr || vk.vkEnumerateInstanceLayerProperties == nullptr ||
      vk.vkEnumerateInstanceExtensionProperties == nullptr) {
    throw DeviceError("the Vulkan loader provides no vkCreateInstance; reinstall libvulkan1");
  }
  return vk;
}

void throwMissing(const char* name, const char* level) {
  throw DeviceError(std::string("the Vulkan ") + level + " provides no " + name +
                    "; update libvulkan1 and the Vulkan driver");
}

}  // namespace

const Dispatch& globalDispatch() {
  // A throwing initialiser leaves the static uninitialised, so a later call retries.
  static const Dispatch kGlobal = loadGlobalFunctions();
  return kGlobal;
}

void loadInstanceFunctions(Dispatch& vk, VkInstance instance, bool debug_utils) {
#define STRATA_VK_LOAD_INSTANCE(name)                                                \
  vk.name = reinterpret_cast<PFN_##name>(vk.vkGetInstanceProcAddr(instance, #name)); \
  if (vk.name == nullptr) throwMissing(#name, "instance");
  STRATA_VK_INSTANCE_FUNCTIONS(STRATA_VK_LOAD_INSTANCE)
#undef STRATA_VK_LOAD_INSTANCE
  if (!debug_utils) return;
#define STRATA_VK_LOAD_DEBUG(name) \
  vk.name = reinterpret_cast<PFN_##name>(vk.vkGetInstanceProcAddr(instance, #name));
  STRATA_VK_DEBUG_UTILS_FUNCTIONS(STRATA_VK_LOAD_DEBUG)
#undef STRATA_VK_LOAD_DEBUG
}

void loadDeviceFunctions(Dispatch& vk, VkDevice device) {
#define STRATA_VK_LOAD_DEVICE(name)                                              \
  vk.name = reinterpret_cast<PFN_##name>(vk.vkGetDeviceProcAddr(device, #name)); \
  if (vk.name == nullptr) throwMissing(#name, "device driver");
  STRATA_VK_DEVICE_FUNCTIONS(STRATA_VK_LOAD_DEVICE)
#undef STRATA_VK_LOAD_DEVICE
}

}  // namespace strata::vk

// Validation-layer messages: counted and kept process-wide, since tests check them per test case
// whichever Context produced them.
#include "strata/vk/internal/validation.h"

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <mutex>
#include <string>
#include <vector>

#include "strata/core/error.h"
#include "strata/vk/internal/enumerate.h"

namespace strata::vk {
namespace {

// Bounded so a runaway error loop cannot eat the host's memory; the count stays exact.
constexpr std::size_t kMaxKeptMessages = 256;

std::atomic<std::uint64_t> g_errors_seen{0};
std::atomic<std::uint64_t> g_errors_acknowledged{0};
std::mutex g_messages_mutex;
std::vector<std::string> g_messages;  // guarded by g_messages_mutex

void keepMessage(const std::string& text) {
  std::lock_guard<std::mutex> lock(g_messages_mutex);
  if (g_messages.size() < kMaxKeptMessages) g_messages.push_back(text);
}

VKAPI_ATTR VkBool32 VKAPI_CALL onValidationMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* /*user_data*/) {
  const std::string text = (data != nullptr && data->pMessage != nullptr)
                               ? std::string(data->pMessage)
                               : std::string("(no message)");
  if (severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT) {
    g_errors_seen.fetch_add(1);
    keepMessage(text);
    std::cerr << "strata: Vulkan validation error: " << text << std::endl;
  } else {
    std::cerr << "strata: Vulkan validation warning: " << text << std::endl;
  }
  return VK_FALSE;  // the spec requires applications to return false
}

}  // namespace

bool validationRequested(const ContextOptions& options) {
  if (options.enable_validation) return true;
  const char* env = std::getenv("STRATA_VALIDATION");
  return env != nullptr && env[0] != '\0' && std::strcmp(env, "0") != 0;
}

void requireValidationLayer(const Dispatch& vk) {
  const auto layers = enumerateChecked<VkLayerProperties>(
      "vkEnumerateInstanceLayerProperties", [&](std::uint32_t* count, VkLayerProperties* data) {
        return vk.vkEnumerateInstanceLayerProperties(count, data);
      });
  for (const VkLayerProperties& layer : layers) {
    if (std::strcmp(layer.layerName, kValidationLayerName) == 0) return;
  }
  throw DeviceError(
      "validation requested but VK_LAYER_KHRONOS_validation is not installed: apt-get install "
      "vulkan-validationlayers");
}

VkDebugUtilsMessengerCreateInfoEXT messengerCreateInfo() {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                         VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType =
      VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  info.pfnUserCallback = &onValidationMessage;
  return info;
}

std::uint64_t validationErrorCount() { return g_errors_seen.load() - g_errors_acknowledged.load(); }

std::vector<std::string> takeValidationMessages() {
  std::lock_guard<std::mutex> lock(g_messages_mutex);
  std::vector<std::string> taken;
  taken.swap(g_messages);
  return taken;
}

void acknowledgeValidationErrors(std::uint64_t count) {
  // Never acknowledge more than were seen, so the count cannot wrap below zero.
  std::uint64_t acknowledged = g_errors_acknowledged.load();
  std::uint64_t wanted = 0;
  do {
    wanted = std::min(acknowledged + count, g_errors_seen.load());
  } while (!g_errors_acknowledged.compare_exchange_weak(acknowledged, wanted));
}

}  // namespace strata::vk

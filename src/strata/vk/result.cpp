// VkResult -> DeviceError with a name and, where there is one, what to do about it.
#include "strata/vk/internal/result.h"

#include "strata/core/error.h"

namespace strata::vk {
namespace {

const char* advice(VkResult result) {
  switch (result) {
    case VK_ERROR_OUT_OF_HOST_MEMORY:
      return "the host ran out of memory";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY:
      return "the device ran out of memory; reduce the map size or pick a device with more "
             "memory (--device)";
    case VK_ERROR_DEVICE_LOST:
      return "the device was lost; the host copy of the map is intact; restart with --device to "
             "pick another device or update the driver";
    case VK_ERROR_INCOMPATIBLE_DRIVER:
      return "no Vulkan driver is installed, or none supports Vulkan 1.2: install "
             "mesa-vulkan-drivers (lavapipe runs the kernels on the CPU) or your GPU vendor's "
             "driver";
    case VK_ERROR_LAYER_NOT_PRESENT:
      return "apt-get install vulkan-validationlayers";
    case VK_ERROR_EXTENSION_NOT_PRESENT:
    case VK_ERROR_FEATURE_NOT_PRESENT:
      return "the driver lacks it; update the driver or pick another device (--device)";
    case VK_ERROR_INITIALIZATION_FAILED:
      return "the driver failed to initialise; check the driver installation";
    default:
      return nullptr;
  }
}

std::string describeFailure(VkResult result, const char* call) {
  std::string message = std::string(call) + " failed: " + resultName(result);
  if (const char* hint = advice(result)) message += std::string(": ") + hint;
  return message;
}

}  // namespace

std::string resultName(VkResult result) {
  switch (result) {
#define STRATA_VK_RESULT_CASE(code) \
  case code:                        \
    return #code;
    STRATA_VK_RESULT_CASE(VK_SUCCESS)
    STRATA_VK_RESULT_CASE(VK_NOT_READY)
    STRATA_VK_RESULT_CASE(VK_TIMEOUT)
    STRATA_VK_RESULT_CASE(VK_INCOMPLETE)
    STRATA_VK_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    STRATA_VK_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    STRATA_VK_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    STRATA_VK_RESULT_CASE(VK_ERROR_DEVICE_LOST)
    STRATA_VK_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    STRATA_VK_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    STRATA_VK_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    STRATA_VK_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    STRATA_VK_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    STRATA_VK_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    STRATA_VK_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    STRATA_VK_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
    STRATA_VK_RESULT_CASE(VK_ERROR_UNKNOWN)
    STRATA_VK_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    STRATA_VK_RESULT_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    STRATA_VK_RESULT_CASE(VK_ERROR_FRAGMENTATION)
    STRATA_VK_RESULT_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    STRATA_VK_RESULT_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
#undef STRATA_VK_RESULT_CASE
    default:
      return "VkResult(" + std::to_string(static_cast<int>(result)) + ")";
  }
}

void check(VkResult result, const char* call) {
  if (result != VK_SUCCESS) throw DeviceError(describeFailure(result, call));
}

void checkFor(VkResult result, const char* call, const std::string& subject) {
  if (result != VK_SUCCESS) throw DeviceError(subject + ": " + describeFailure(result, call));
}

}  // namespace strata::vk

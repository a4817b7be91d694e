#pragma once
// Private: the Khronos validation layer and the process-wide record of the errors it reports.
#include "strata/vk/loader.h"

namespace strata::vk {

constexpr const char* kValidationLayerName = "VK_LAYER_KHRONOS_validation";

/// options.enable_validation, or env STRATA_VALIDATION set to anything but "" or "0".
bool validationRequested(const ContextOptions& options);

/// Throws DeviceError with the apt-get line when the layer is not installed.
void requireValidationLayer(const Dispatch& vk);

/// Messenger settings: warnings and errors; errors are counted (validationErrorCount) and kept
/// (takeValidationMessages); both are printed to stderr.
VkDebugUtilsMessengerCreateInfoEXT messengerCreateInfo();

}  // namespace strata::vk

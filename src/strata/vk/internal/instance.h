#pragma once
// Private: the VkInstance (Vulkan 1.2, with the validation layer when asked) and its messenger.
#include "strata/vk/loader.h"

namespace strata::vk {

/// Creates the instance and loads its functions into `vk` (which must hold the global ones).
/// `debug_utils` tells whether VK_EXT_debug_utils was enabled (always with validation, otherwise
/// when the loader offers it: object names then show in debuggers such as RenderDoc).
VkInstance createInstance(Dispatch& vk, bool validation, bool& debug_utils);

/// The messenger that counts validation errors (validation.h). Needs debug utils.
VkDebugUtilsMessengerEXT createMessenger(const Dispatch& vk, VkInstance instance);

}  // namespace strata::vk

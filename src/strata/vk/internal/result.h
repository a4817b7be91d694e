#pragma once
// Private: VkResult names and the errors made from them.
#include <string>

#include "strata/vk/vk.h"

namespace strata::vk {

/// "VK_ERROR_DEVICE_LOST", ... ("VkResult(<n>)" for codes this file does not know).
std::string resultName(VkResult result);

/// Like check(), with the object the call was about in front: "<subject>: <call> failed: ...".
void checkFor(VkResult result, const char* call, const std::string& subject);

}  // namespace strata::vk

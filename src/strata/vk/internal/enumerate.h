#pragma once
// Private: the two-call "count, then fill" pattern of vkEnumerate*/vkGet* functions.
#include <cstdint>
#include <vector>

#include "strata/vk/internal/result.h"

namespace strata::vk {

/// `call(count*, data*)` returns VkResult; retried while the list grows between the two calls.
template <typename T, typename Call>
std::vector<T> enumerateChecked(const char* call_name, Call call) {
  std::vector<T> items;
  VkResult result = VK_INCOMPLETE;
  while (result == VK_INCOMPLETE) {
    std::uint32_t count = 0;
    check(call(&count, static_cast<T*>(nullptr)), call_name);
    items.resize(count);
    result = call(&count, items.data());
    items.resize(count);
  }
  check(result, call_name);
  return items;
}

/// For the void vkGet* functions (no VkResult).
template <typename T, typename Call>
std::vector<T> enumerateAll(Call call) {
  std::uint32_t count = 0;
  call(&count, static_cast<T*>(nullptr));
  std::vector<T> items(count);
  call(&count, items.data());
  items.resize(count);
  return items;
}

}  // namespace strata::vk

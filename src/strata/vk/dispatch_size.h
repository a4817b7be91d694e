#pragma once
// Workgroup counts of compute dispatches: one definition for every kernel's dispatch code.
#include <cstdint>
#include <type_traits>

namespace strata::vk {

/// The largest workgroup count per dimension every Vulkan device accepts
/// (maxComputeWorkGroupCount's guaranteed minimum); larger counts spill into y.
inline constexpr std::uint32_t kMaxGroupsPerDimension = 65535;

/// ceil(a / b) for a >= 0, b > 0, in the common type of the two: the groups of b invocations that
/// cover a items.
template <typename A, typename B>
constexpr std::common_type_t<A, B> divideUp(A a, B b) {
  static_assert(std::is_integral_v<A> && std::is_integral_v<B>, "divideUp counts integers");
  using T = std::common_type_t<A, B>;
  return (static_cast<T>(a) + static_cast<T>(b) - 1) / static_cast<T>(b);
}

}  // namespace strata::vk

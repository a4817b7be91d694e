#pragma once
// Injected device-memory exhaustion, FOR TESTS ONLY: lets a test make Buffer::create fail exactly
// as a real vkAllocateMemory returning VK_ERROR_OUT_OF_DEVICE_MEMORY would (same error path, same
// DeviceError), at a chosen allocation, to check what a failure in the middle of a session keeps.
// Off by default; production code never arms it. Zero cost when unarmed: one relaxed atomic load
// per allocation. docs/faults.md lists the faults and the tests that use them.
// Thread safety: every function is thread safe (a process-wide counter under a mutex).
#include <cstdint>
#include <limits>
#include <string>

namespace strata::vk {

struct AllocationFault {
  /// Matching allocations that still succeed before the first injected failure.
  std::uint64_t skip = 0;
  /// Matching allocations that fail after those (kForever: every one until disarmed, like a
  /// device that stays full).
  std::uint64_t count = 1;
  /// Only buffers whose debug name contains this text match ("" matches every buffer).
  std::string name_contains;
};

class FaultInjection {
 public:
  static constexpr std::uint64_t kForever = std::numeric_limits<std::uint64_t>::max();

  /// Arms `fault` from now on, replacing any armed one and resetting both counters.
  static void armAllocationFailure(const AllocationFault& fault);
  static void disarm();
  /// Matching allocations seen, and failures injected, since the last arm.
  static std::uint64_t allocationsSeen();
  static std::uint64_t failuresInjected();

  /// Called by Buffer::create before vkAllocateMemory: true when this allocation must fail.
  static bool failAllocation(const std::string& buffer_name);
};

/// Arms a fault for the lifetime of the object (disarms on destruction, also when a test fails).
class ScopedAllocationFault {
 public:
  explicit ScopedAllocationFault(const AllocationFault& fault) {
    FaultInjection::armAllocationFailure(fault);
  }
  ~ScopedAllocationFault() { FaultInjection::disarm(); }
  ScopedAllocationFault(const ScopedAllocationFault&) = delete;
  ScopedAllocationFault& operator=(const ScopedAllocationFault&) = delete;
};

}  // namespace strata::vk

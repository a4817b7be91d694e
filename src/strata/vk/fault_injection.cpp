// Injected allocation failures for tests (fault_injection.h).
#include "strata/vk/fault_injection.h"

#include <atomic>
#include <mutex>

namespace strata::vk {
namespace {

struct ArmedFault {
  std::mutex mutex;
  std::atomic<bool> armed{false};  // read without the mutex: the unarmed fast path
  AllocationFault fault;
  std::uint64_t seen = 0;
  std::uint64_t injected = 0;
};

ArmedFault& state() {
  static ArmedFault armed_fault;
  return armed_fault;
}

}  // namespace

void FaultInjection::armAllocationFailure(const AllocationFault& fault) {
  ArmedFault& s = state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  s.fault = fault;
  s.seen = 0;
  s.injected = 0;
  s.armed.store(true);
}

void FaultInjection::disarm() {
  ArmedFault& s = state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  s.armed.store(false);
}

std::uint64_t FaultInjection::allocationsSeen() {
  ArmedFault& s = state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  return s.seen;
}

std::uint64_t FaultInjection::failuresInjected() {
  ArmedFault& s = state();
  const std::lock_guard<std::mutex> lock(s.mutex);
  return s.injected;
}

bool FaultInjection::failAllocation(const std::string& buffer_name) {
  ArmedFault& s = state();
  if (!s.armed.load(std::memory_order_relaxed)) return false;
  const std::lock_guard<std::mutex> lock(s.mutex);
  if (!s.armed.load() || buffer_name.find(s.fault.name_contains) == std::string::npos) {
    return false;
  }
  const std::uint64_t index = s.seen++;
  const bool fail = index >= s.fault.skip && index - s.fault.skip < s.fault.count;
  if (fail) ++s.injected;
  return fail;
}

}  // namespace strata::vk

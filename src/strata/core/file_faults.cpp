// Injected file-system failures for tests (file_faults.h).
#include "strata/core/file_faults.h"

#include <array>
#include <atomic>

namespace strata {
namespace {

constexpr std::size_t kStepCount = 4;
// One pending errno per step (0: none) and a count of armed steps for the unarmed fast path.
std::array<std::atomic<int>, kStepCount> pending{};
std::atomic<int> armed_steps{0};

std::size_t indexOf(FileStep step) { return static_cast<std::size_t>(step); }

}  // namespace

void FileFaultInjection::arm(FileStep step, int error_number) {
  if (error_number <= 0) return;
  if (pending[indexOf(step)].exchange(error_number) == 0) armed_steps.fetch_add(1);
}

void FileFaultInjection::disarm() {
  for (std::atomic<int>& p : pending) {
    if (p.exchange(0) != 0) armed_steps.fetch_sub(1);
  }
}

int FileFaultInjection::take(FileStep step) {
  if (armed_steps.load(std::memory_order_relaxed) == 0) return 0;
  const int error_number = pending[indexOf(step)].exchange(0);
  if (error_number != 0) armed_steps.fetch_sub(1);
  return error_number;
}

}  // namespace strata

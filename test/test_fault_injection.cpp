// The test-only injection points themselves (vk::FaultInjection, FileFaultInjection): which calls
// fail, counted exactly across threads, and nothing fails once disarmed.
#include <gtest/gtest.h>

#include <cerrno>
#include <thread>
#include <vector>

#include "strata/core/file_faults.h"
#include "strata/vk/fault_injection.h"

namespace strata {
namespace {

using vk::AllocationFault;
using vk::FaultInjection;

std::vector<bool> outcomes(const std::string& name, int calls) {
  std::vector<bool> failed;
  for (int i = 0; i < calls; ++i) failed.push_back(FaultInjection::failAllocation(name));
  return failed;
}

TEST(FaultInjection, SkipsThenFailsCountAllocationsThenNoneOnceDisarmed) {
  EXPECT_EQ(outcomes("any", 3), (std::vector<bool>{false, false, false})) << "off by default";
  {
    const vk::ScopedAllocationFault fault(AllocationFault{2, 3, ""});
    EXPECT_EQ(outcomes("any", 7),
              (std::vector<bool>{false, false, true, true, true, false, false}));
    EXPECT_EQ(FaultInjection::allocationsSeen(), 7u);
    EXPECT_EQ(FaultInjection::failuresInjected(), 3u);
  }
  EXPECT_EQ(outcomes("any", 3), (std::vector<bool>{false, false, false})) << "disarmed";
}

TEST(FaultInjection, OnlyBuffersWhoseNameMatchesCountAndFail) {
  const vk::ScopedAllocationFault fault(
      AllocationFault{0, FaultInjection::kForever, "TSDF voxel pool"});
  EXPECT_FALSE(FaultInjection::failAllocation("block hash table"));
  EXPECT_TRUE(FaultInjection::failAllocation("TSDF voxel pool"));
  EXPECT_TRUE(FaultInjection::failAllocation("TSDF voxel pool"));
  EXPECT_EQ(FaultInjection::allocationsSeen(), 2u);
}

TEST(FaultInjection, ConcurrentAllocationsFailExactlyCountTimes) {
  const vk::ScopedAllocationFault fault(AllocationFault{10, 100, ""});
  constexpr int kThreads = 4;
  constexpr int kCallsPerThread = 1000;
  std::vector<std::thread> threads;
  std::vector<int> failures(kThreads, 0);
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&failures, t] {
      for (int i = 0; i < kCallsPerThread; ++i) failures[t] += FaultInjection::failAllocation("b");
    });
  }
  for (std::thread& thread : threads) thread.join();
  int total = 0;
  for (const int f : failures) total += f;
  EXPECT_EQ(total, 100);
  EXPECT_EQ(FaultInjection::allocationsSeen(), std::uint64_t{kThreads * kCallsPerThread});
}

TEST(FileFaultInjection, EachArmedStepFailsOnceWithItsErrno) {
  EXPECT_EQ(FileFaultInjection::take(FileStep::kWrite), 0) << "off by default";
  {
    const ScopedFileFault fault(FileStep::kWrite, ENOSPC);
    FileFaultInjection::arm(FileStep::kRename, EIO);
    EXPECT_EQ(FileFaultInjection::take(FileStep::kOpen), 0);
    EXPECT_EQ(FileFaultInjection::take(FileStep::kWrite), ENOSPC);
    EXPECT_EQ(FileFaultInjection::take(FileStep::kWrite), 0) << "once";
    FileFaultInjection::arm(FileStep::kFsync, EIO);
  }
  // Disarming cleared the rename and fsync faults that were still armed.
  EXPECT_EQ(FileFaultInjection::take(FileStep::kRename), 0);
  EXPECT_EQ(FileFaultInjection::take(FileStep::kFsync), 0);
}

}  // namespace
}  // namespace strata

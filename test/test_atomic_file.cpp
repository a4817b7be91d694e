// writeFileAtomically's housekeeping: temporaries of killed writers (`<name>.tmp.<pid>[.<call>]` whose
// process is gone) are removed by the next write of the same file; a live writer's is kept.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "strata/core/atomic_file.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

/// The id of a process that has exited (and been reaped): no process has it now, barring reuse
/// in the microseconds since.
pid_t deadPid() {
  const pid_t pid = fork();
  if (pid == 0) _exit(0);
  waitpid(pid, nullptr, 0);
  return pid;
}

void touch(const fs::path& path) { std::ofstream(path) << "partial"; }

TEST(AtomicFile, TemporariesOfKilledWritersAreRemovedAndLiveOnesKept) {
  const fs::path dir = fs::temp_directory_path() / ("strata_atomic_" + std::to_string(getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path target = dir / "map.strata";
  const fs::path killed = dir / ("map.strata.tmp." + std::to_string(deadPid()) + ".3");
  const fs::path live = dir / ("map.strata.tmp." + std::to_string(getppid()));
  const fs::path other_file = dir / ("other.strata.tmp." + std::to_string(deadPid()));
  for (const fs::path& p : {killed, live, other_file}) touch(p);

  writeFileAtomically(target.string(), {1, 2, 3});

  EXPECT_EQ(readFile(target.string()), (std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_FALSE(fs::exists(killed)) << "a killed writer's temporary is removed";
  EXPECT_TRUE(fs::exists(live)) << "a live process's temporary is its own business";
  EXPECT_TRUE(fs::exists(other_file)) << "another file's temporaries are left to its writes";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata

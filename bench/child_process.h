#pragma once
// Child processes of the benchmarks: started with posix_spawn, waited for, asked to stop.
// Thread safety: thread safe (no shared state), but waitProcess must be called once per child.
#include <sys/types.h>

#include <string>
#include <vector>

namespace strata::bench {

/// Starts `program` with `args`. `output_path` not empty: stdout goes there (created or truncated;
/// "/dev/null" discards), and stderr too when `stderr_too`; otherwise both stay this process's.
/// Returns the child's pid; throws Error naming the program when it cannot start.
pid_t spawnProcess(const std::string& program, const std::vector<std::string>& args,
                   const std::string& output_path = "", bool stderr_too = false);

/// Blocks until `pid` exits; its exit code, 128 + signal number when a signal ended it.
int waitProcess(pid_t pid);

/// Non-blocking: true when `pid` has exited, its code (as waitProcess) in `*code`.
bool processExited(pid_t pid, int* code);

/// This executable's path (/proc/self/exe).
std::string selfExecutable();

}  // namespace strata::bench

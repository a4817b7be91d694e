#include "child_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "strata/core/error.h"

extern char** environ;

namespace strata::bench {
namespace {

int exitCode(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : 1;
}

/// waitpid, retried when a signal interrupts it; the pid or 0 (WNOHANG, still running).
pid_t waitRetrying(pid_t pid, int* status, int flags) {
  for (;;) {
    const pid_t done = waitpid(pid, status, flags);
    if (done >= 0) return done;
    if (errno != EINTR) throw Error(std::string("waitpid failed: ") + std::strerror(errno));
  }
}

}  // namespace

pid_t spawnProcess(const std::string& program, const std::vector<std::string>& args,
                   const std::string& output_path, bool stderr_too) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(program.c_str()));
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!output_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, output_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (stderr_too) posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, program.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) throw Error("could not start " + program + ": " + std::strerror(spawned));
  return pid;
}

int waitProcess(pid_t pid) {
  int status = 0;
  waitRetrying(pid, &status, 0);
  return exitCode(status);
}

bool processExited(pid_t pid, int* code) {
  int status = 0;
  if (waitRetrying(pid, &status, WNOHANG) == 0) return false;
  *code = exitCode(status);
  return true;
}

std::string selfExecutable() { return std::filesystem::read_symlink("/proc/self/exe").string(); }

}  // namespace strata::bench

#include "strata/core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "strata/core/error.h"
#include "strata/core/file_faults.h"

namespace strata {
namespace {

std::string systemReason() { return std::strerror(errno); }

std::array<std::uint32_t, 256> makeCrcTable() {
  std::array<std::uint32_t, 256> table{};
  for (std::uint32_t i = 0; i < 256; ++i) {
    std::uint32_t c = i;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
    table[i] = c;
  }
  return table;
}

constexpr const char* kTempInfix = ".tmp.";

/// The writer's pid in `name` = `prefix` + `<pid>.<call>` or `<pid>` (digits); 0 when it is not
/// such a name.
pid_t temporaryOwner(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string rest = name.substr(prefix.size());
  const std::size_t dot = rest.find('.');
  const std::string pid = rest.substr(0, dot);
  const std::string call = dot == std::string::npos ? std::string() : rest.substr(dot + 1);
  const auto digits = [](const std::string& t) {
    return !t.empty() && t.size() <= 19 && t.find_first_not_of("0123456789") == std::string::npos;
  };
  if (!digits(pid) || pid.size() > 9 || (dot != std::string::npos && !digits(call))) return 0;
  return static_cast<pid_t>(std::stol(pid));
}

/// A process killed between creating its temporary and the rename (SIGKILL, power loss) leaves
/// `<name>.tmp.<pid>.<call>` behind; the next write of `<name>` removes those whose process is
/// gone, so kills never pile temporaries up. A live writer's temporary (another process, or
/// another thread of this one, saving the same file) is kept. NOTE: a writer in another pid namespace looks gone; its rename then fails
/// cleanly and the file stays whole.
void removeStaleTemporaries(const std::filesystem::path& target) {
  namespace fs = std::filesystem;
  const std::string prefix = target.filename().string() + kTempInfix;
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code error;  // best effort: a leftover never blocks the save
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const pid_t pid = temporaryOwner(it->path().filename().string(), prefix);
    if (pid <= 0) continue;
    if (pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      fs::remove(it->path(), ignored);
    }
  }
}

/// NOTE: rename() is durable only once the folder's entry is on disk: without this fsync a
/// power loss after the rename can bring back the old file (or no file) on some filesystems.
void syncFolder(const std::filesystem::path& target, const std::string& path) {
  const std::string folder = target.parent_path().empty() ? "." : target.parent_path().string();
  const int fd = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY);
  if (fd < 0) {
    throw Error("'" + path + "' was replaced, but its folder cannot be opened: " + systemReason());
  }
  const int rc = ::fsync(fd);
  const std::string reason = systemReason();
  ::close(fd);
  if (rc != 0) {
    throw Error("'" + path + "' was replaced, but flushing its folder failed: " + reason);
  }
}

// Every system call of a write goes through one of these, so a test can stand in for a full or
// read-only file system (file_faults.h).
int injectedError(FileStep step) {
  const int error_number = FileFaultInjection::take(step);
  if (error_number != 0) errno = error_number;
  return error_number;
}

std::uint64_t nextTempNumber() {
  static std::atomic<std::uint64_t> next{0};
  return next.fetch_add(1);
}

/// The temporary beside the target: removed on destruction unless renamed over the target, so no
/// failure leaves it behind.
class TempFile {
 public:
  explicit TempFile(const std::string& target) : target_(target) {
    const std::filesystem::path t(target);
    temp_ = (t.parent_path() / (t.filename().string() + kTempInfix + std::to_string(::getpid()) + "." +
                                std::to_string(nextTempNumber())))
                .string();
    fd_ = injectedError(FileStep::kOpen) != 0
              ? -1
              : ::open(temp_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    created_ = fd_ >= 0;
    if (!created_) {
      const std::string folder = t.parent_path().empty() ? "." : t.parent_path().string();
      fail("cannot create a file in folder '" + folder + "'");
    }
  }
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (created_ && !renamed_) ::unlink(temp_.c_str());
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  void write(const std::vector<std::uint8_t>& bytes) {
    std::size_t written = 0;
    while (written < bytes.size()) {
      const ssize_t n = injectedError(FileStep::kWrite) != 0
                            ? -1
                            : ::write(fd_, bytes.data() + written, bytes.size() - written);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) fail("writing '" + temp_ + "' failed");
      written += static_cast<std::size_t>(n);
    }
  }

  /// fsync, then close (always, so a failed flush leaks no descriptor).
  void flushAndClose() {
    const bool synced = injectedError(FileStep::kFsync) == 0 && ::fsync(fd_) == 0;
    const int sync_errno = errno;
    const bool closed = ::close(fd_) == 0;
    fd_ = -1;
    if (!synced) {
      errno = sync_errno;
      fail("flushing '" + temp_ + "' to disk failed");
    }
    if (!closed) fail("closing '" + temp_ + "' failed");
  }

  void renameOverTarget() {
    if (injectedError(FileStep::kRename) != 0 || ::rename(temp_.c_str(), target_.c_str()) != 0) {
      fail("renaming '" + temp_ + "' over it failed");
    }
    renamed_ = true;
  }

 private:
  /// Error naming the target, the step and the system's reason (errno as the failed call left
  /// it); the destructor then removes the temporary.
  [[noreturn]] void fail(const std::string& step) {
    const std::string reason = systemReason();
    throw Error("cannot write '" + target_ + "': " + step + ": " + reason + "; '" + target_ +
                "' is unchanged");
  }

  std::string target_;
  std::string temp_;
  int fd_ = -1;
  bool created_ = false;
  bool renamed_ = false;
};

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> kTable = makeCrcTable();
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = kTable[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

void writeFileAtomically(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  removeStaleTemporaries(std::filesystem::path(path));
  TempFile temp(path);
  temp.write(bytes);
  temp.flushAndClose();
  temp.renameOverTarget();
  syncFolder(std::filesystem::path(path), path);
}

void writeTextAtomically(const std::string& path, const std::string& text) {
  writeFileAtomically(path, std::vector<std::uint8_t>(text.begin(), text.end()));
}

std::vector<std::uint8_t> readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot open '" + path + "': " + systemReason());
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw InputError("cannot read '" + path + "': not a regular file");
  in.seekg(0, std::ios::beg);
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size)) {
    throw InputError("cannot read '" + path + "': read failed");
  }
  return bytes;
}

}  // namespace strata

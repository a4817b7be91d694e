#include "core/atomic_file.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "core/error.h"

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

/// The writer's pid in `name` = `prefix` + digits; 0 when it is not such a name.
pid_t temporaryOwner(const std::string& name, const std::string& prefix) {
  if (name.size() <= prefix.size() || name.size() > prefix.size() + 9) return 0;
  if (name.compare(0, prefix.size(), prefix) != 0) return 0;
  const std::string digits = name.substr(prefix.size());
  if (digits.find_first_not_of("0123456789") != std::string::npos) return 0;
  return static_cast<pid_t>(std::stol(digits));
}

/// A process killed between creating its temporary and the rename (SIGKILL, power loss) leaves
/// `<name>.tmp.<pid>` behind; the next write of `<name>` removes those whose process is gone, so
/// kills never pile temporaries up. A live writer's temporary (another process saving the same
/// file) is kept. NOTE: a writer in another pid namespace looks gone; its rename then fails
/// cleanly and the file stays whole.
void removeStaleTemporaries(const std::filesystem::path& target) {
  namespace fs = std::filesystem;
  const std::string prefix = target.filename().string() + kTempInfix;
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  std::error_code error;  // best effort: a leftover never blocks the save
  for (fs::directory_iterator it(folder, error), end; !error && it != end; it.increment(error)) {
    const pid_t pid = temporaryOwner(it->path().filename().string(), prefix);
    if (pid <= 0) continue;
    if (pid == ::getpid() || (::kill(pid, 0) != 0 && errno == ESRCH)) {
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

}  // namespace

std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc) {
  static const std::array<std::uint32_t, 256> kTable = makeCrcTable();
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) crc = kTable[(crc ^ data[i]) & 0xFFu] ^ (crc >> 8);
  return ~crc;
}

void writeFileAtomically(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  removeStaleTemporaries(target);
  const fs::path temp = target.parent_path() /
                        (target.filename().string() + kTempInfix + std::to_string(::getpid()));
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw Error("cannot write '" + path + "': " + systemReason());
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0) {
      if (errno == EINTR) continue;
      const std::string reason = systemReason();
      ::close(fd);
      ::unlink(temp.c_str());
      throw Error("cannot write '" + path + "': " + reason);
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    const std::string reason = systemReason();
    ::unlink(temp.c_str());
    throw Error("cannot write '" + path + "': flushing failed: " + reason);
  }
  if (::rename(temp.c_str(), target.c_str()) != 0) {
    const std::string reason = systemReason();
    ::unlink(temp.c_str());
    throw Error("cannot write '" + path + "': rename failed: " + reason);
  }
  syncFolder(target, path);
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

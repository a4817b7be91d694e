#pragma once
// File sizes checked before a whole file (or a text file line by line) is read into memory, so a
// huge or endless file (a device, a FIFO, a corrupt size) is refused instead of exhausting memory.
// Each reader keeps its own limit, a named constexpr next to its call, and passes name and value.
#include <cstdint>
#include <string>
#include <vector>

namespace strata {

/// A named size limit: the name appears in the error so a user knows which constant refused.
struct FileSizeLimit {
  const char* name;
  std::uint64_t max_bytes;
};

/// Throws InputError "<path>: <what> not found" when `path` is not a regular file, and
/// "<path>: <size> bytes is over <limit.name> = <limit.max_bytes> bytes" when it is too large.
/// Returns the size in bytes.
std::uint64_t checkFileSize(const std::string& path, const FileSizeLimit& limit,
                            const std::string& what);

/// checkFileSize, then the whole file. InputError naming the path when it cannot be read.
std::vector<std::uint8_t> readFileBounded(const std::string& path, const FileSizeLimit& limit,
                                          const std::string& what);

/// The same as text (bytes unchanged).
std::string readTextBounded(const std::string& path, const FileSizeLimit& limit,
                            const std::string& what);

}  // namespace strata

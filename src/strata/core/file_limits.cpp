#include "strata/core/file_limits.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "strata/core/error.h"

namespace strata {
namespace {

template <typename Buffer>
Buffer readBounded(const std::string& path, const FileSizeLimit& limit, const std::string& what) {
  const std::uint64_t size = checkFileSize(path, limit, what);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open " + what + ": " + std::strerror(errno));
  Buffer bytes(static_cast<std::size_t>(size), 0);
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  // NOTE: a file that shrank while being read is refused rather than returned short.
  if (static_cast<std::uint64_t>(in.gcount()) != size) {
    throw InputError(path + ": cannot read " + what + " (" + std::to_string(in.gcount()) + " of " +
                     std::to_string(size) + " bytes)");
  }
  return bytes;
}

}  // namespace

std::uint64_t checkFileSize(const std::string& path, const FileSizeLimit& limit,
                            const std::string& what) {
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) {
    throw InputError(path + ": " + what + " not found (or not a regular file)");
  }
  const std::uint64_t size = std::filesystem::file_size(path, error);
  if (error) throw InputError(path + ": cannot stat " + what + ": " + error.message());
  if (size > limit.max_bytes) {
    throw InputError(path + ": " + what + " of " + std::to_string(size) + " bytes is over " +
                     limit.name + " = " + std::to_string(limit.max_bytes) + " bytes");
  }
  return size;
}

std::vector<std::uint8_t> readFileBounded(const std::string& path, const FileSizeLimit& limit,
                                          const std::string& what) {
  return readBounded<std::vector<std::uint8_t>>(path, limit, what);
}

std::string readTextBounded(const std::string& path, const FileSizeLimit& limit,
                            const std::string& what) {
  return readBounded<std::string>(path, limit, what);
}

}  // namespace strata

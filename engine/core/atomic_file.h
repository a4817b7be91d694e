#pragma once
// Whole-file I/O with the guarantees map and mesh files need.
#include <cstdint>
#include <string>
#include <vector>

namespace strata {

/// Writes `bytes` to `path` atomically: a temporary `<path>.tmp.<pid>` in the same folder, flushed
/// to disk, renamed over `path`, then the folder flushed (the rename is durable when this returns).
/// A reader sees the old file or the whole new one, never a torn one, even if the process is
/// killed at any moment. Temporaries left by killed writers of `path` are removed first. On
/// failure the temporary is removed, `path` is untouched, and Error names the path and the
/// system's reason. Thread safety: one writer per path within a process.
void writeFileAtomically(const std::string& path, const std::vector<std::uint8_t>& bytes);

/// Reads a whole file; InputError naming the path when it cannot.
std::vector<std::uint8_t> readFile(const std::string& path);

/// CRC-32 (IEEE 802.3 polynomial, reflected), as used by zip and PNG.
std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0);

}  // namespace strata

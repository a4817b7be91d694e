#pragma once
// Whole-file I/O with the guarantees map and mesh files need.
#include <cstdint>
#include <string>
#include <vector>

namespace strata {

/// Writes `bytes` to `path` atomically: a temporary `<path>.tmp.<pid>.<call>` in the same folder,
/// flushed to disk, renamed over `path`, then the folder flushed (the rename is durable when this
/// returns). A reader sees the old file or the whole new one, never a torn one, even if the process
/// is killed at any moment; temporaries left by killed writers of `path` are removed first. On any
/// failure (full disk, read-only folder, failed flush or rename) the temporary is removed, `path`
/// keeps its previous bytes (or stays absent), and Error says "cannot write '<path>': <step>:
/// <system reason>; '<path>' is unchanged", the step naming the folder when the temporary cannot
/// be created. A failed folder flush after the rename says the file was replaced.
/// Thread safe (concurrent writes of one path: the last rename wins, each file whole).
void writeFileAtomically(const std::string& path, const std::vector<std::uint8_t>& bytes);

/// Reads a whole file; InputError naming the path when it cannot.
std::vector<std::uint8_t> readFile(const std::string& path);

/// writeFileAtomically for text (the bytes of `text` as they are).
void writeTextAtomically(const std::string& path, const std::string& text);

/// CRC-32 (IEEE 802.3 polynomial, reflected), as used by zip and PNG.
std::uint32_t crc32(const std::uint8_t* data, std::size_t size, std::uint32_t crc = 0);

}  // namespace strata

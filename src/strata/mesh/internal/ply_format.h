#pragma once
// PLY header model and value cursors (internal to readPly).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace strata::detail {

enum class PlyType { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat32, kFloat64 };

struct PlyProperty {
  std::string name;
  PlyType type = PlyType::kFloat32;  // of the items, for lists
  bool is_list = false;
  PlyType count_type = PlyType::kUint8;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  bool binary = true;  // binary_little_endian; false = ascii
  std::vector<PlyElement> elements;
  std::size_t data_offset = 0;  // first byte after "end_header\n"
};

/// Parses the header at the start of `data`. Throws InputError (without the path) when corrupt.
PlyHeader parsePlyHeader(const std::string& data);

std::size_t plyTypeSize(PlyType type);

/// Little-endian binary values. Throws InputError "truncated" past the end.
class PlyBinaryCursor {
 public:
  PlyBinaryCursor(const std::string& data, std::size_t offset) : data_(data), pos_(offset) {}
  double read(PlyType type);
  /// Whether `count` items of at least `min_item_bytes` can still follow.
  bool canHold(std::size_t count, std::size_t min_item_bytes) const;

 private:
  const std::string& data_;
  std::size_t pos_;
};

/// Whitespace-separated ascii values. Throws InputError on a missing or malformed number.
class PlyAsciiCursor {
 public:
  PlyAsciiCursor(const std::string& data, std::size_t offset) : data_(data), pos_(offset) {}
  double read(PlyType type);
  bool canHold(std::size_t count, std::size_t min_item_bytes) const;

 private:
  const std::string& data_;
  std::size_t pos_;
};

}  // namespace strata::detail

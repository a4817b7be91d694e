#pragma once
// The viewer's wire format: one binary WebSocket message per scene item. Layout (little-endian):
// u32 L, L bytes of a JSON object (the header), zero bytes up to a multiple of 4, then the payload.
// The header's "arrays" lists each typed array of the payload as {name, type: "f32"|"u32"|"u8",
// count (elements), offset (bytes from the payload's start, a multiple of 4)}. The page
// (web/src/main.js) reads it with typed-array views, without copying. Pure functions; thread safe.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace strata::view {

/// One encoded message, shared (never copied) by every client it is sent to.
using Message = std::shared_ptr<const std::string>;

struct WireArray {
  enum class Type { kF32, kU32, kU8 };
  std::string name;
  Type type = Type::kF32;
  const void* data = nullptr;
  std::size_t count = 0;  // elements
};

/// The message of `header` (a JSON object; its "arrays" is written here) and `arrays`.
Message encodeMessage(nlohmann::json header, const std::vector<WireArray>& arrays = {});

/// A decoded message: the header and the payload's bytes (the page decodes in JavaScript; this is
/// for the C++ clients of the stream, the tests among them).
struct DecodedMessage {
  nlohmann::json header;
  std::string payload;
};
/// InputError when `bytes` is not a well-formed message (short, header past the end, bad JSON,
/// an array outside the payload).
DecodedMessage decodeMessage(const std::string& bytes);

}  // namespace strata::view

#include "view/wire.h"

#include <cstring>

#include "strata/core/error.h"

namespace strata::view {
namespace {

std::size_t elementSize(WireArray::Type type) { return type == WireArray::Type::kU8 ? 1 : 4; }

const char* typeName(WireArray::Type type) {
  switch (type) {
    case WireArray::Type::kF32: return "f32";
    case WireArray::Type::kU32: return "u32";
    case WireArray::Type::kU8: return "u8";
  }
  return "?";
}

std::size_t padTo4(std::size_t n) { return (n + 3) & ~std::size_t{3}; }

}  // namespace

Message encodeMessage(nlohmann::json header, const std::vector<WireArray>& arrays) {
  nlohmann::json described = nlohmann::json::array();
  std::size_t payload_bytes = 0;
  for (const WireArray& a : arrays) {
    described.push_back({{"name", a.name}, {"type", typeName(a.type)}, {"count", a.count},
                         {"offset", payload_bytes}});
    payload_bytes += padTo4(a.count * elementSize(a.type));
  }
  header["arrays"] = std::move(described);
  const std::string text = header.dump();
  const std::size_t payload_start = padTo4(4 + text.size());
  auto bytes = std::make_shared<std::string>(payload_start + payload_bytes, '\0');
  const auto length = static_cast<std::uint32_t>(text.size());
  for (int i = 0; i < 4; ++i) (*bytes)[i] = static_cast<char>((length >> (8 * i)) & 0xffu);
  std::memcpy(bytes->data() + 4, text.data(), text.size());
  std::size_t offset = payload_start;
  for (const WireArray& a : arrays) {
    const std::size_t n = a.count * elementSize(a.type);
    if (n > 0) std::memcpy(bytes->data() + offset, a.data, n);
    offset += padTo4(n);
  }
  return bytes;
}

DecodedMessage decodeMessage(const std::string& bytes) {
  if (bytes.size() < 4) throw InputError("viewer message of " + std::to_string(bytes.size()) + " bytes: shorter than its 4-byte header length");
  std::uint32_t length = 0;
  for (int i = 0; i < 4; ++i) length |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << (8 * i);
  if (length > bytes.size() - 4) throw InputError("viewer message: header of " + std::to_string(length) + " bytes runs past the message's " + std::to_string(bytes.size()));
  DecodedMessage m;
  m.header = nlohmann::json::parse(bytes.begin() + 4, bytes.begin() + 4 + length, nullptr, false);
  if (m.header.is_discarded() || !m.header.is_object()) throw InputError("viewer message: header is not a JSON object");
  const std::size_t start = std::min(padTo4(4 + length), bytes.size());
  m.payload = bytes.substr(start);
  if (m.header.contains("arrays")) {
    for (const auto& a : m.header["arrays"]) {
      const std::string type = a.value("type", "");
      const std::size_t size = type == "u8" ? 1 : 4;
      const auto offset = a.value("offset", std::size_t{0});
      const auto count = a.value("count", std::size_t{0});
      if (offset > m.payload.size() || count > (m.payload.size() - offset) / size)
        throw InputError("viewer message: array '" + a.value("name", "") + "' outside the payload");
    }
  }
  return m;
}

}  // namespace strata::view

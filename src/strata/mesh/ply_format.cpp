#include "strata/mesh/internal/ply_format.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "strata/core/error.h"

namespace strata::detail {
namespace {

PlyType parseType(const std::string& name) {
  static const std::pair<const char*, PlyType> kNames[] = {
      {"char", PlyType::kInt8},      {"int8", PlyType::kInt8},       {"uchar", PlyType::kUint8},
      {"uint8", PlyType::kUint8},    {"short", PlyType::kInt16},     {"int16", PlyType::kInt16},
      {"ushort", PlyType::kUint16},  {"uint16", PlyType::kUint16},   {"int", PlyType::kInt32},
      {"int32", PlyType::kInt32},    {"uint", PlyType::kUint32},     {"uint32", PlyType::kUint32},
      {"float", PlyType::kFloat32},  {"float32", PlyType::kFloat32}, {"double", PlyType::kFloat64},
      {"float64", PlyType::kFloat64}};
  for (const auto& [text, type] : kNames) {
    if (name == text) return type;
  }
  throw InputError("corrupt header: unknown property type '" + name + "'");
}

PlyProperty parseProperty(std::istringstream& words) {
  PlyProperty property;
  std::string type;
  words >> type;
  if (type == "list") {
    std::string count_type, item_type;
    words >> count_type >> item_type;
    property.is_list = true;
    property.count_type = parseType(count_type);
    property.type = parseType(item_type);
  } else {
    property.type = parseType(type);
  }
  if (!(words >> property.name)) throw InputError("corrupt header: property without a name");
  return property;
}

void parseHeaderLine(const std::string& line, PlyHeader& header, bool& has_format) {
  std::istringstream words(line);
  std::string keyword;
  words >> keyword;
  if (keyword.empty() || keyword == "comment" || keyword == "obj_info") return;
  if (keyword == "format") {
    std::string format;
    words >> format;
    if (format != "binary_little_endian" && format != "ascii") {
      throw InputError("unsupported format '" + format + "' (binary_little_endian or ascii)");
    }
    header.binary = format == "binary_little_endian";
    has_format = true;
  } else if (keyword == "element") {
    PlyElement element;
    long long count = -1;
    if (!(words >> element.name >> count) || count < 0) {
      throw InputError("corrupt header: bad element line '" + line + "'");
    }
    element.count = static_cast<std::size_t>(count);
    header.elements.push_back(element);
  } else if (keyword == "property") {
    if (header.elements.empty()) throw InputError("corrupt header: property before any element");
    header.elements.back().properties.push_back(parseProperty(words));
  } else {
    throw InputError("corrupt header: unknown keyword '" + keyword + "'");
  }
}

}  // namespace

std::size_t plyTypeSize(PlyType type) {
  switch (type) {
    case PlyType::kInt8:
    case PlyType::kUint8:
      return 1;
    case PlyType::kInt16:
    case PlyType::kUint16:
      return 2;
    case PlyType::kInt32:
    case PlyType::kUint32:
    case PlyType::kFloat32:
      return 4;
    case PlyType::kFloat64:
      return 8;
  }
  return 0;
}

PlyHeader parsePlyHeader(const std::string& data) {
  if (data.compare(0, 4, "ply\n") != 0 && data.compare(0, 5, "ply\r\n") != 0) {
    throw InputError("not a PLY file (no 'ply' magic line)");
  }
  PlyHeader header;
  bool has_format = false;
  std::size_t pos = data.find('\n') + 1;
  while (true) {
    const std::size_t end = data.find('\n', pos);
    if (end == std::string::npos) throw InputError("truncated header (no end_header)");
    std::string line = data.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos = end + 1;
    if (line == "end_header") break;
    parseHeaderLine(line, header, has_format);
  }
  if (!has_format) throw InputError("corrupt header: no format line");
  header.data_offset = pos;
  return header;
}

double PlyBinaryCursor::read(PlyType type) {
  const std::size_t size = plyTypeSize(type);
  if (data_.size() - pos_ < size)
    throw InputError("truncated data at byte " + std::to_string(pos_));
  const char* p = data_.data() + pos_;
  pos_ += size;
  auto as = [p](auto value) {
    std::memcpy(&value, p, sizeof(value));
    return static_cast<double>(value);
  };
  switch (type) {
    case PlyType::kInt8:
      return as(std::int8_t{});
    case PlyType::kUint8:
      return as(std::uint8_t{});
    case PlyType::kInt16:
      return as(std::int16_t{});
    case PlyType::kUint16:
      return as(std::uint16_t{});
    case PlyType::kInt32:
      return as(std::int32_t{});
    case PlyType::kUint32:
      return as(std::uint32_t{});
    case PlyType::kFloat32:
      return as(float{});
    case PlyType::kFloat64:
      return as(double{});
  }
  return 0.0;
}

bool PlyBinaryCursor::canHold(std::size_t count, std::size_t min_item_bytes) const {
  return min_item_bytes == 0 || count <= (data_.size() - pos_) / min_item_bytes;
}

double PlyAsciiCursor::read(PlyType /*type*/) {
  while (pos_ < data_.size() && std::isspace(static_cast<unsigned char>(data_[pos_]))) ++pos_;
  if (pos_ >= data_.size()) throw InputError("truncated ascii data");
  const char* begin = data_.c_str() + pos_;
  char* end = nullptr;
  const double value = std::strtod(begin, &end);
  if (end == begin) throw InputError("corrupt ascii value at byte " + std::to_string(pos_));
  pos_ += static_cast<std::size_t>(end - begin);
  return value;
}

bool PlyAsciiCursor::canHold(std::size_t count, std::size_t min_item_bytes) const {
  // Each ascii value takes at least one character plus a separator (the last may lack it).
  return count <= (data_.size() - pos_ + 1) / std::max<std::size_t>(1, min_item_bytes);
}

}  // namespace strata::detail

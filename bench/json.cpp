#include "json.h"

#include <cmath>
#include <cstdio>
#include <vector>

#include "strata/core/atomic_file.h"

namespace strata::bench {
namespace {

void writeString(std::string& out, const std::string& text) {
  out += '"';
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof(escaped), "\\u%04x", static_cast<unsigned>(c));
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  out += '"';
}

void writeNumber(std::string& out, double value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  // NOTE: 6 significant digits; timings are not more precise than that.
  char text[32];
  std::snprintf(text, sizeof(text), "%.6g", value);
  out += text;
}

void newline(std::string& out, int depth) {
  out += '\n';
  out.append(static_cast<std::size_t>(depth) * 2, ' ');
}

}  // namespace

Json Json::object() {
  Json json;
  json.kind_ = Kind::kObject;
  return json;
}

Json Json::array() {
  Json json;
  json.kind_ = Kind::kArray;
  return json;
}

Json Json::numbers(const std::vector<double>& values) {
  Json json = array();
  for (const double value : values) json.push(value);
  return json;
}

Json& Json::set(const std::string& key, Json value) {
  kind_ = Kind::kObject;
  members_.emplace_back(key, std::move(value));
  return *this;
}

Json& Json::push(Json value) {
  kind_ = Kind::kArray;
  members_.emplace_back(std::string(), std::move(value));
  return *this;
}

std::string Json::dump() const {
  std::string out;
  write(out, 0);
  return out;
}

void Json::write(std::string& out, int depth) const {
  switch (kind_) {
    case Kind::kNull:
      out += "null";
      return;
    case Kind::kBool:
      out += bool_ ? "true" : "false";
      return;
    case Kind::kNumber:
      writeNumber(out, number_);
      return;
    case Kind::kInteger:
      out += std::to_string(integer_);
      return;
    case Kind::kString:
      writeString(out, string_);
      return;
    case Kind::kArray:
    case Kind::kObject:
      break;
  }
  const bool is_object = kind_ == Kind::kObject;
  out += is_object ? '{' : '[';
  for (std::size_t i = 0; i < members_.size(); ++i) {
    if (i > 0) out += ',';
    newline(out, depth + 1);
    if (is_object) {
      writeString(out, members_[i].first);
      out += ": ";
    }
    members_[i].second.write(out, depth + 1);
  }
  if (!members_.empty()) newline(out, depth);
  out += is_object ? '}' : ']';
}

void emitReport(const Json& report, const std::string& out_path) {
  const std::string text = report.dump() + "\n";
  std::fputs(text.c_str(), stdout);
  if (out_path.empty()) return;
  writeFileAtomically(out_path, std::vector<std::uint8_t>(text.begin(), text.end()));
  std::fprintf(stderr, "wrote %s\n", out_path.c_str());
}

}  // namespace strata::bench

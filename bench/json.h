#pragma once
// A minimal ordered JSON value for benchmark reports: objects keep insertion order so reports
// read top-down and diff cleanly between runs. Non-finite numbers are written as null.
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace strata::bench {

class Json {
 public:
  Json() = default;  // null
  Json(bool value) : kind_(Kind::kBool), bool_(value) {}
  Json(double value) : kind_(Kind::kNumber), number_(value) {}
  template <typename T,
            std::enable_if_t<std::is_integral_v<T> && !std::is_same_v<T, bool>, int> = 0>
  Json(T value) : kind_(Kind::kInteger), integer_(static_cast<std::int64_t>(value)) {}
  Json(const char* value) : kind_(Kind::kString), string_(value) {}
  Json(std::string value) : kind_(Kind::kString), string_(std::move(value)) {}

  static Json object();
  static Json array();
  static Json numbers(const std::vector<double>& values);

  /// Object member (appended; keys are not deduplicated). Returns *this for chaining.
  Json& set(const std::string& key, Json value);
  /// Array element. Returns *this for chaining.
  Json& push(Json value);

  /// Pretty-printed with two-space indentation, ending without a newline.
  std::string dump() const;

 private:
  enum class Kind { kNull, kBool, kNumber, kInteger, kString, kArray, kObject };
  void write(std::string& out, int depth) const;

  Kind kind_ = Kind::kNull;
  bool bool_ = false;
  double number_ = 0.0;
  std::int64_t integer_ = 0;
  std::string string_;
  std::vector<std::pair<std::string, Json>> members_;  // object members or array elements
};

/// Prints `report` on stdout and, when `out_path` is not empty, also writes it there atomically
/// (a note on stderr says so).
void emitReport(const Json& report, const std::string& out_path);

}  // namespace strata::bench

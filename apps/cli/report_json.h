#pragma once
// The JSON the commands write (reports, summaries, objects.json): nlohmann::ordered_json values,
// so keys stay in the order they are set, and the text they are written as.
#include <Eigen/Core>
#include <charconv>
#include <nlohmann/json.hpp>
#include <string>

namespace strata::apps {

using Json = nlohmann::ordered_json;

/// `j` indented by two spaces, no trailing newline. NaN and infinities come out as null; bytes
/// that are not UTF-8 (a file name, say) as U+FFFD instead of an exception.
inline std::string jsonText(const Json& j) {
  return j.dump(2, ' ', false, Json::error_handler_t::replace);
}

/// jsonText with the trailing newline a file ends with.
inline std::string jsonFileText(const Json& j) { return jsonText(j) + "\n"; }

/// The value of `text`, a JSON value another writer returned as text (the order of its keys
/// kept). Throws nlohmann::json::parse_error when it is not JSON.
inline Json parseJson(const std::string& text) { return Json::parse(text); }

/// `v` as the double with `v`'s own shortest text: 0.05f as 0.05 rather than
/// 0.05000000074505806. NaN and infinities stay what they are.
inline double jsonFloat(float v) {
  char text[32];
  const std::to_chars_result end = std::to_chars(text, text + sizeof(text), v);
  double out = static_cast<double>(v);
  std::from_chars(text, end.ptr, out);
  return out;
}
/// Doubles need no rounding: this keeps one from passing a double and losing its digits.
double jsonFloat(double v) = delete;

/// [x, y, z] of a float vector, each as jsonFloat.
inline Json jsonVector(const Eigen::Vector3f& v) {
  return Json::array({jsonFloat(v.x()), jsonFloat(v.y()), jsonFloat(v.z())});
}
/// [x, y, z] of a double vector.
inline Json jsonVector(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }

}  // namespace strata::apps

#pragma once
// Line-aware access to a parsed YAML document: every read names the file, the line and the field
// path when the value is missing or wrong, e.g.
//   room.yaml:12: objects[3].size: expected 3 numbers, got 2
// Internal to the world parser (yaml-cpp stays out of public headers).
#include <yaml-cpp/yaml.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace strata::sim {

class YamlField {
 public:
  /// The document root; `file` is the name used in messages.
  YamlField(YAML::Node node, std::string file);

  const std::string& path() const { return path_; }
  /// 1-based line of this value (of the enclosing value when this one is missing).
  int line() const { return line_; }

  /// "file:line: path" for messages.
  std::string where() const;
  /// Throws InputError "file:line: path: what".
  [[noreturn]] void fail(const std::string& what) const;

  // Maps.
  bool has(const std::string& key) const;
  /// Required member: fails "path.key: missing" at this map's line.
  YamlField get(const std::string& key) const;
  std::optional<YamlField> find(const std::string& key) const;
  /// Fails on the first key not in `allowed`, suggesting the nearest allowed key (typos).
  void allowKeys(const std::vector<std::string>& allowed) const;
  void expectMap() const;

  // Sequences.
  std::vector<YamlField> items() const;

  // Scalars.
  std::string text() const;
  bool boolean() const;
  double number() const;  // finite
  double positive() const;
  double nonNegative() const;
  double fraction() const;  // in [0, 1]
  long long integer(long long lo, long long hi) const;
  std::uint64_t unsignedInteger() const;
  /// Exactly `count` finite numbers: "expected 3 numbers, got 2".
  std::vector<double> numbers(int count) const;
  Eigen::Vector2d vec2() const;
  Eigen::Vector3d vec3() const;
  /// [r, g, b], integers 0-255.
  std::array<std::uint8_t, 3> rgb() const;

  // Optional members with defaults (validated like the required forms).
  double numberOr(const std::string& key, double fallback) const;
  double positiveOr(const std::string& key, double fallback) const;
  double fractionOr(const std::string& key, double fallback) const;
  bool booleanOr(const std::string& key, bool fallback) const;

 private:
  YamlField(YAML::Node node, std::string path, std::string file, int line);
  YamlField child(const YAML::Node& node, const std::string& path) const;
  std::string childPath(const std::string& key) const;

  YAML::Node node_;
  std::string path_;
  std::string file_;
  int line_ = 1;
};

}  // namespace strata::sim

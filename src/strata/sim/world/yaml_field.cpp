#include "strata/sim/world/internal/yaml_field.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "strata/core/error.h"

namespace strata::sim {
namespace {

int markLine(const YAML::Node& node, int fallback) {
  if (!node.IsDefined()) return fallback;
  const YAML::Mark mark = node.Mark();
  return mark.line >= 0 ? mark.line + 1 : fallback;  // yaml-cpp counts from 0
}

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1 : 0)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string describe(const YAML::Node& node) {
  if (node.IsScalar()) return "'" + node.Scalar() + "'";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a map";
  return "nothing";
}

}  // namespace

YamlField::YamlField(YAML::Node node, std::string file) : YamlField(node, "", std::move(file), 1) {
  line_ = markLine(node_, 1);
}

YamlField::YamlField(YAML::Node node, std::string path, std::string file, int line)
    : node_(node), path_(std::move(path)), file_(std::move(file)), line_(line) {}

YamlField YamlField::child(const YAML::Node& node, const std::string& path) const {
  return YamlField(node, path, file_, markLine(node, line_));
}

std::string YamlField::childPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

std::string YamlField::where() const {
  return file_ + ":" + std::to_string(line_) + (path_.empty() ? "" : ": " + path_);
}

void YamlField::fail(const std::string& what) const { throw InputError(where() + ": " + what); }

void YamlField::expectMap() const {
  if (!node_.IsMap()) fail("expected a map of key: value, got " + describe(node_));
}

bool YamlField::has(const std::string& key) const {
  return node_.IsMap() && node_[key].IsDefined() && !node_[key].IsNull();
}

YamlField YamlField::get(const std::string& key) const {
  expectMap();
  if (!has(key)) {
    YamlField(node_, childPath(key), file_, line_).fail("missing (required)");
  }
  return child(node_[key], childPath(key));
}

std::optional<YamlField> YamlField::find(const std::string& key) const {
  if (!has(key)) return std::nullopt;
  return child(node_[key], childPath(key));
}

void YamlField::allowKeys(const std::vector<std::string>& allowed) const {
  expectMap();
  std::set<std::string> seen;
  for (const auto& entry : node_) {
    // NOTE: YAML allows any node as a key ({[4, 3]: 1}); ours are names, so refuse the rest here
    // rather than let as<std::string>() throw a YAML exception past the parser.
    if (!entry.first.IsScalar()) {
      child(entry.first, path_).fail("a key must be text, got " + describe(entry.first));
    }
    const std::string key = entry.first.Scalar();
    // NOTE: YAML forbids a key twice in one map but yaml-cpp keeps both and reads the first, so a
    // second value would be silently ignored.
    if (!seen.insert(key).second) child(entry.first, childPath(key)).fail("given twice");
    if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
    std::string hint;
    std::size_t best = 3;  // suggest only close matches (typos)
    for (const std::string& candidate : allowed) {
      const std::size_t d = editDistance(key, candidate);
      if (d < best) best = d, hint = " (did you mean '" + candidate + "'?)";
    }
    child(entry.first, childPath(key)).fail("unknown key" + hint);
  }
}

std::vector<YamlField> YamlField::items() const {
  if (!node_.IsSequence()) fail("expected a list, got " + describe(node_));
  std::vector<YamlField> out;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    out.push_back(child(node_[i], path_ + "[" + std::to_string(i) + "]"));
  }
  return out;
}

std::string YamlField::text() const {
  if (!node_.IsScalar()) fail("expected text, got " + describe(node_));
  return node_.Scalar();
}

bool YamlField::boolean() const {
  bool value = false;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, value)) {
    fail("expected true or false, got " + describe(node_));
  }
  return value;
}

double YamlField::number() const {
  double value = 0.0;
  if (!node_.IsScalar() || !YAML::convert<double>::decode(node_, value) || !std::isfinite(value)) {
    fail("expected a number, got " + describe(node_));
  }
  return value;
}

double YamlField::positive() const {
  const double value = number();
  if (!(value > 0.0)) fail("must be positive, got " + node_.Scalar());
  return value;
}

double YamlField::nonNegative() const {
  const double value = number();
  if (value < 0.0) fail("must not be negative, got " + node_.Scalar());
  return value;
}

double YamlField::fraction() const {
  const double value = number();
  if (value < 0.0 || value > 1.0) fail("must be in [0, 1], got " + node_.Scalar());
  return value;
}

long long YamlField::integer(long long lo, long long hi) const {
  long long value = 0;
  if (!node_.IsScalar() || !YAML::convert<long long>::decode(node_, value)) {
    fail("expected a whole number, got " + describe(node_));
  }
  if (value < lo || value > hi) {
    fail("must be in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
         node_.Scalar());
  }
  return value;
}

std::uint64_t YamlField::unsignedInteger() const {
  std::uint64_t value = 0;
  if (!node_.IsScalar() || node_.Scalar().find('-') != std::string::npos ||
      !YAML::convert<std::uint64_t>::decode(node_, value)) {
    fail("expected a non-negative whole number, got " + describe(node_));
  }
  return value;
}

std::vector<double> YamlField::numbers(int count) const {
  const std::string expected = "expected " + std::to_string(count) + " numbers";
  if (!node_.IsSequence()) fail(expected + ", got " + describe(node_));
  if (node_.size() != static_cast<std::size_t>(count)) {
    fail(expected + ", got " + std::to_string(node_.size()));
  }
  std::vector<double> out;
  for (const YamlField& item : items()) out.push_back(item.number());
  return out;
}

Eigen::Vector2d YamlField::vec2() const {
  const std::vector<double> v = numbers(2);
  return {v[0], v[1]};
}

Eigen::Vector3d YamlField::vec3() const {
  const std::vector<double> v = numbers(3);
  return {v[0], v[1], v[2]};
}

std::array<std::uint8_t, 3> YamlField::rgb() const {
  if (!node_.IsSequence() || node_.size() != 3) {
    fail("expected 3 whole numbers 0-255 (red, green, blue)");
  }
  std::array<std::uint8_t, 3> out{};
  const std::vector<YamlField> channels = items();
  for (int c = 0; c < 3; ++c) out[c] = static_cast<std::uint8_t>(channels[c].integer(0, 255));
  return out;
}

double YamlField::numberOr(const std::string& key, double fallback) const {
  return has(key) ? get(key).number() : fallback;
}

double YamlField::positiveOr(const std::string& key, double fallback) const {
  return has(key) ? get(key).positive() : fallback;
}

double YamlField::fractionOr(const std::string& key, double fallback) const {
  return has(key) ? get(key).fraction() : fallback;
}

bool YamlField::booleanOr(const std::string& key, bool fallback) const {
  return has(key) ? get(key).boolean() : fallback;
}

}  // namespace strata::sim

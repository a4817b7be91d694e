// data.csv and ground-truth parsing for the EuRoC reader (io/euroc_parse.h).
#include <charconv>
#include <cmath>
#include <string_view>

#include "strata/core/error.h"
#include "strata/io/euroc_parse.h"

namespace strata::euroc {
namespace {

struct Row {
  int line = 0;
  std::vector<std::string_view> fields;
};

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

/// Data rows split on `separators` ("," for CSV, " \t" for TUM, where runs count once).
std::vector<Row> splitRows(const std::string& text, const char* separators) {
  const bool whitespace = separators[0] == ' ';
  std::vector<Row> rows;
  std::size_t begin = 0;
  for (int line = 1; begin < text.size(); ++line) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    const std::string_view content = trim(std::string_view(text).substr(begin, end - begin));
    begin = end + 1;
    if (content.empty() || content.front() == '#') continue;
    Row row{line, {}};
    std::size_t start = 0;
    while (start <= content.size()) {
      std::size_t stop = content.find_first_of(separators, start);
      if (stop == std::string_view::npos) stop = content.size();
      const std::string_view field = trim(content.substr(start, stop - start));
      if (!whitespace || !field.empty()) row.fields.push_back(field);
      start = stop + 1;
    }
    rows.push_back(std::move(row));
  }
  return rows;
}

std::string where(const std::string& name, const Row& row) {
  return name + ":" + std::to_string(row.line) + ": ";
}

void requireColumns(const std::string& name, const Row& row, std::size_t count,
                    const char* layout) {
  if (row.fields.size() != count) {
    throw InputError(where(name, row) + std::to_string(row.fields.size()) + " columns, expected " +
                     std::to_string(count) + " (" + layout + ")");
  }
}

std::int64_t parseTimestampNs(const std::string& name, const Row& row) {
  const std::string_view field = row.fields.at(0);
  std::int64_t value = 0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (error != std::errc() || end != field.data() + field.size() || value < 0) {
    throw InputError(where(name, row) + "timestamp '" + std::string(field) +
                     "' is not a non-negative integer of nanoseconds");
  }
  return value;
}

/// from_chars accepts "nan" and "inf"; callers decide whether those are allowed.
double parseDouble(const std::string& name, const Row& row, std::size_t column) {
  const std::string_view field = row.fields.at(column);
  double value = 0.0;
  const auto [end, error] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (error != std::errc() || end != field.data() + field.size()) {
    throw InputError(where(name, row) + "column " + std::to_string(column + 1) + " '" +
                     std::string(field) + "' is not a number");
  }
  return value;
}

/// Strictly increasing timestamps; `previous` < 0 before the first row.
void checkOrder(const std::string& name, const Row& row, std::int64_t timestamp_ns,
                std::int64_t* previous) {
  if (*previous >= 0 && timestamp_ns <= *previous) {
    throw InputError(where(name, row) + "timestamp " + std::to_string(timestamp_ns) +
                     (timestamp_ns == *previous ? " repeats" : " goes back from") +
                     " the previous row's " + std::to_string(*previous) +
                     " (rows must be in strictly increasing time)");
  }
  *previous = timestamp_ns;
}

Eigen::Isometry3d poseFrom(const Eigen::Vector3d& p, Eigen::Quaterniond q, const std::string& at) {
  if (!p.allFinite() || !q.coeffs().allFinite() || q.norm() < 1e-9) {
    throw InputError(at + "pose has a non-finite value or a zero quaternion");
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = p;
  return T;
}

}  // namespace

std::vector<ImageRow> parseImageCsv(const std::string& text, const std::string& name) {
  std::vector<ImageRow> images;
  std::int64_t previous = -1;
  for (const Row& row : splitRows(text, ",")) {
    requireColumns(name, row, 2, "timestamp [ns],filename");
    ImageRow image{parseTimestampNs(name, row), std::string(row.fields[1])};
    if (image.filename.empty() || image.filename.find('/') != std::string::npos ||
        image.filename.find('\\') != std::string::npos || image.filename == "..") {
      throw InputError(where(name, row) + "filename '" + image.filename +
                       "' must be a plain file name inside data/");
    }
    checkOrder(name, row, image.timestamp_ns, &previous);
    images.push_back(std::move(image));
  }
  return images;
}

ImuCsv parseImuCsv(const std::string& text, const std::string& name) {
  ImuCsv csv;
  std::int64_t previous = -1;
  for (const Row& row : splitRows(text, ",")) {
    requireColumns(name, row, 7, "timestamp [ns],w_x,w_y,w_z [rad/s],a_x,a_y,a_z [m/s^2]");
    ImuSample sample;
    sample.timestamp_ns = parseTimestampNs(name, row);
    checkOrder(name, row, sample.timestamp_ns, &previous);
    for (int i = 0; i < 3; ++i) {
      sample.gyro_rad_s[i] = parseDouble(name, row, static_cast<std::size_t>(1 + i));
      sample.accel_mps2[i] = parseDouble(name, row, static_cast<std::size_t>(4 + i));
    }
    ++csv.rows;
    if (!sample.gyro_rad_s.allFinite() || !sample.accel_mps2.allFinite()) {
      ++csv.nonfinite_skipped;
      continue;
    }
    csv.samples.push_back(sample);
  }
  return csv;
}

std::vector<GroundTruthState> parseGroundTruthCsv(const std::string& text,
                                                  const std::string& name) {
  std::vector<GroundTruthState> states;
  std::int64_t previous = -1;
  for (const Row& row : splitRows(text, ",")) {
    if (row.fields.size() != 8) {
      requireColumns(name, row, 17, "timestamp, p xyz, q wxyz, v xyz, bw xyz, ba xyz");
    }
    GroundTruthState state;
    state.timestamp_ns = parseTimestampNs(name, row);
    checkOrder(name, row, state.timestamp_ns, &previous);
    double v[16];
    for (std::size_t i = 1; i < row.fields.size(); ++i) {
      v[i - 1] = parseDouble(name, row, i);
      if (!std::isfinite(v[i - 1])) {
        throw InputError(where(name, row) + "column " + std::to_string(i + 1) + " is not finite");
      }
    }
    state.T_W_B =
        poseFrom({v[0], v[1], v[2]}, Eigen::Quaterniond(v[3], v[4], v[5], v[6]), where(name, row));
    if (row.fields.size() == 17) {
      state.has_velocity_and_biases = true;
      state.velocity_W = {v[7], v[8], v[9]};
      state.gyro_bias = {v[10], v[11], v[12]};
      state.accel_bias = {v[13], v[14], v[15]};
    }
    states.push_back(state);
  }
  return states;
}

std::vector<GroundTruthState> parseGroundTruthTum(const std::string& text,
                                                  const std::string& name) {
  std::vector<GroundTruthState> states;
  std::int64_t previous = -1;
  for (const Row& row : splitRows(text, " \t")) {
    requireColumns(name, row, 8, "timestamp[s] tx ty tz qx qy qz qw");
    double v[8];
    for (std::size_t i = 0; i < 8; ++i) {
      v[i] = parseDouble(name, row, i);
      if (!std::isfinite(v[i])) {
        throw InputError(where(name, row) + "column " + std::to_string(i + 1) + " is not finite");
      }
    }
    if (v[0] < 0.0 || v[0] > 9.2e9) {
      throw InputError(where(name, row) + "timestamp must be in [0, 9.2e9] seconds");
    }
    GroundTruthState state;
    state.timestamp_ns = std::llround(v[0] * 1e9);
    checkOrder(name, row, state.timestamp_ns, &previous);
    state.T_W_B =
        poseFrom({v[1], v[2], v[3]}, Eigen::Quaterniond(v[7], v[4], v[5], v[6]), where(name, row));
    states.push_back(state);
  }
  return states;
}

}  // namespace strata::euroc

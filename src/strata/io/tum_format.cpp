#include "strata/io/tum_format.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "strata/core/error.h"
#include "strata/core/file_limits.h"

namespace strata::tum {
namespace {

struct Line {
  int number = 0;
  std::vector<std::string> tokens;
};

// Checked before a list or trajectory is read: a TUM groundtruth.txt of an hour at 100 Hz is ~30 MB.
constexpr FileSizeLimit kMaxTumTextFileBytes{"kMaxTumTextFileBytes", std::uint64_t{256} << 20};

std::ifstream openBounded(const std::string& path) {
  checkFileSize(path, kMaxTumTextFileBytes, "TUM text file");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": file not found or not readable");
  return in;
}

/// Non-comment, non-blank lines of a text stream, split on whitespace.
std::vector<Line> readLines(std::istream& in) {
  std::vector<Line> lines;
  std::string text;
  for (int number = 1; std::getline(in, text); ++number) {
    std::istringstream fields(text);
    Line line{number, {}};
    for (std::string token; fields >> token;) line.tokens.push_back(token);
    if (line.tokens.empty() || line.tokens.front().front() == '#') continue;
    lines.push_back(std::move(line));
  }
  return lines;
}

std::string where(const std::string& path, const Line& line) {
  return path + ":" + std::to_string(line.number) + ": ";
}

/// strtod (accepts "nan"/"inf", reported below as non-finite rather than as malformed).
double parseNumber(const std::string& token, const std::string& context) {
  char* end = nullptr;
  const double value = std::strtod(token.c_str(), &end);
  if (end == token.c_str() || *end != '\0')
    throw InputError(context + "'" + token + "' is not a number");
  if (!std::isfinite(value)) throw InputError(context + "non-finite value '" + token + "'");
  return value;
}

}  // namespace

std::vector<TimedFile> readFileList(const std::string& path) {
  std::ifstream in = openBounded(path);
  return readFileList(in, path);
}

std::vector<TimedFile> readFileList(std::istream& in, const std::string& path) {
  std::vector<TimedFile> files;
  for (const Line& line : readLines(in)) {
    if (line.tokens.size() < 2) {
      throw InputError(where(path, line) + "expected 'timestamp filename', got " +
                       std::to_string(line.tokens.size()) + " field(s)");
    }
    files.push_back({parseNumber(line.tokens[0], where(path, line)), line.tokens[1]});
  }
  std::stable_sort(files.begin(), files.end(), [](const TimedFile& a, const TimedFile& b) {
    return a.timestamp_s < b.timestamp_s;
  });
  return files;
}

std::vector<TimedPose> readTrajectory(const std::string& path) {
  std::ifstream in = openBounded(path);
  return readTrajectory(in, path);
}

std::vector<TimedPose> readTrajectory(std::istream& in, const std::string& path) {
  std::vector<TimedPose> poses;
  for (const Line& line : readLines(in)) {
    if (line.tokens.size() != 8) {
      throw InputError(where(path, line) + "expected 'timestamp tx ty tz qx qy qz qw', got " +
                       std::to_string(line.tokens.size()) + " field(s)");
    }
    double values[8];
    for (int i = 0; i < 8; ++i) values[i] = parseNumber(line.tokens[i], where(path, line));
    const std::optional<Eigen::Isometry3d> T_W_C = poseFromTum(values + 1);
    if (!T_W_C) throw InputError(where(path, line) + "quaternion qx qy qz qw is zero");
    poses.push_back({values[0], *T_W_C});
  }
  std::stable_sort(poses.begin(), poses.end(), [](const TimedPose& a, const TimedPose& b) {
    return a.timestamp_s < b.timestamp_s;
  });
  return poses;
}

std::optional<Eigen::Isometry3d> poseFromTum(const double values[7]) {
  Eigen::Quaterniond q(values[6], values[3], values[4], values[5]);  // w, x, y, z
  const double norm = q.norm();
  if (!std::isfinite(norm) || norm < 1e-12) return std::nullopt;
  q.coeffs() /= norm;
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  T_W_C.linear() = q.toRotationMatrix();
  T_W_C.translation() = Eigen::Vector3d(values[0], values[1], values[2]);
  return T_W_C;
}

std::string poseToTum(const Eigen::Isometry3d& T_W_C) {
  const Eigen::Vector3d t = T_W_C.translation();
  const Eigen::Quaterniond q(T_W_C.rotation());
  char text[256];
  std::snprintf(text, sizeof(text), "%.9f %.9f %.9f %.9f %.9f %.9f %.9f", t.x(), t.y(), t.z(),
                q.x(), q.y(), q.z(), q.w());
  return text;
}

std::optional<std::size_t> nearestWithin(const std::vector<double>& sorted_s, double t_s,
                                         double max_difference_s) {
  const auto after = std::lower_bound(sorted_s.begin(), sorted_s.end(), t_s);
  std::optional<std::size_t> best;
  double best_difference = max_difference_s + 1e-9;  // NOTE: tolerance for decimal round-off
  for (auto it : {after - (after != sorted_s.begin() ? 1 : 0), after}) {
    if (it == sorted_s.end()) continue;
    const double difference = std::abs(*it - t_s);
    if (difference <= best_difference) {
      best = static_cast<std::size_t>(it - sorted_s.begin());
      best_difference = difference;
    }
  }
  return best;
}

std::vector<double> timestampsOf(const std::vector<TimedFile>& files) {
  std::vector<double> out;
  out.reserve(files.size());
  for (const TimedFile& f : files) out.push_back(f.timestamp_s);
  return out;
}

std::vector<double> timestampsOf(const std::vector<TimedPose>& poses) {
  std::vector<double> out;
  out.reserve(poses.size());
  for (const TimedPose& p : poses) out.push_back(p.timestamp_s);
  return out;
}

}  // namespace strata::tum

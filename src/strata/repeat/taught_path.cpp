#include "strata/repeat/taught_path.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

#include "strata/core/error.h"
#include "strata/io/tum_format.h"
#include "strata/repeat/teach_recording.h"

namespace strata::repeat {
namespace {

namespace fs = std::filesystem;

float distanceToSegment(const Eigen::Vector3f& p, const Eigen::Vector3f& a,
                        const Eigen::Vector3f& b) {
  const Eigen::Vector3f ab = b - a;
  const float l2 = ab.squaredNorm();
  const float t = l2 > 0.0f ? std::clamp((p - a).dot(ab) / l2, 0.0f, 1.0f) : 0.0f;
  return (a + t * ab - p).norm();
}

void simplifyRange(const std::vector<Eigen::Vector3f>& points, std::size_t first, std::size_t last,
                   float tolerance_m, std::vector<bool>& keep) {
  if (last <= first + 1) return;
  float worst = -1.0f;
  std::size_t worst_i = first;
  for (std::size_t i = first + 1; i < last; ++i) {
    const float d = distanceToSegment(points[i], points[first], points[last]);
    if (d > worst) {
      worst = d;
      worst_i = i;
    }
  }
  if (worst <= tolerance_m) return;
  keep[worst_i] = true;
  simplifyRange(points, first, worst_i, tolerance_m, keep);
  simplifyRange(points, worst_i, last, tolerance_m, keep);
}

std::vector<tum::TimedPose> readPoses(const fs::path& path) {
  if (!fs::is_regular_file(path)) {
    throw InputError("teach folder: '" + path.string() + "' is missing (not a teach folder?)");
  }
  return tum::readTrajectory(path.string());
}

}  // namespace

float distanceToPolyline(const Eigen::Vector3f& p, const std::vector<Eigen::Vector3f>& polyline) {
  if (polyline.empty()) return std::numeric_limits<float>::infinity();
  if (polyline.size() == 1) return (polyline[0] - p).norm();
  float best = std::numeric_limits<float>::infinity();
  for (std::size_t i = 1; i < polyline.size(); ++i) {
    best = std::min(best, distanceToSegment(p, polyline[i - 1], polyline[i]));
  }
  return best;
}

std::vector<Eigen::Vector3f> simplifyPolyline(const std::vector<Eigen::Vector3f>& points,
                                              float tolerance_m) {
  if (points.size() < 3) return points;
  std::vector<bool> keep(points.size(), false);
  keep.front() = keep.back() = true;
  simplifyRange(points, 0, points.size() - 1, tolerance_m, keep);
  std::vector<Eigen::Vector3f> out;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (keep[i]) out.push_back(points[i]);
  }
  return out;
}

Eigen::Vector3f TaughtPath::at(double s) const {
  if (p_M.empty()) return Eigen::Vector3f::Zero();
  if (s <= 0.0) return p_M.front();
  if (s >= length_m()) return p_M.back();
  const std::size_t i = static_cast<std::size_t>(std::upper_bound(s_m.begin(), s_m.end(), s) -
                                                 s_m.begin());  // s_m[i - 1] <= s < s_m[i]
  const double span = s_m[i] - s_m[i - 1];
  const float f = span > 0.0 ? static_cast<float>((s - s_m[i - 1]) / span) : 0.0f;
  return p_M[i - 1] + f * (p_M[i] - p_M[i - 1]);
}

std::vector<Eigen::Vector3f> TaughtPath::between(double s0, double s1) const {
  s0 = std::clamp(s0, 0.0, length_m());
  s1 = std::clamp(s1, s0, length_m());
  std::vector<Eigen::Vector3f> out{at(s0)};
  for (std::size_t i = 0; i < p_M.size(); ++i) {
    if (s_m[i] > s0 && s_m[i] < s1 && (p_M[i] - out.back()).norm() > 1e-4f) out.push_back(p_M[i]);
  }
  const Eigen::Vector3f end = at(s1);
  if ((end - out.back()).norm() > 1e-4f) out.push_back(end);
  return out;
}

TaughtPath TaughtPath::load(const std::string& dir) {
  const std::vector<tum::TimedPose> taught = readPoses(fs::path(dir) / kTaughtPathFile);
  const std::vector<tum::TimedPose> truth = readPoses(fs::path(dir) / "groundtruth.txt");
  if (taught.size() < 2) {
    throw InputError("teach folder '" + dir + "': taught_path.txt holds fewer than 2 poses");
  }
  if (truth.size() != taught.size()) {
    throw InputError("teach folder '" + dir + "': groundtruth.txt has " +
                     std::to_string(truth.size()) + " poses, taught_path.txt " +
                     std::to_string(taught.size()));
  }
  TaughtPath path;
  double s = 0.0;
  for (std::size_t i = 0; i < taught.size(); ++i) {
    if (std::abs(truth[i].timestamp_s - taught[i].timestamp_s) > 1e-3) {
      throw InputError("teach folder '" + dir +
                       "': groundtruth.txt and taught_path.txt differ "
                       "in their timestamps");
    }
    const Eigen::Vector3f p = taught[i].T_W_C.translation().cast<float>();
    if (!path.p_M.empty()) s += (p - path.p_M.back()).norm();
    const Eigen::Vector3d forward = taught[i].T_W_C.linear().col(2);
    path.timestamp_s.push_back(taught[i].timestamp_s);
    path.p_M.push_back(p);
    path.yaw_rad.push_back(static_cast<float>(std::atan2(forward.y(), forward.x())));
    path.p_W.push_back(truth[i].T_W_C.translation().cast<float>());
    path.s_m.push_back(s);
  }
  return path;
}

}  // namespace strata::repeat

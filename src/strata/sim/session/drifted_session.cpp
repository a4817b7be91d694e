#include "strata/sim/session/drifted_session.h"

#include <filesystem>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/io/odometry_frame_file.h"
#include "strata/io/tum_format.h"
#include "strata/io/tum_writer.h"

namespace strata::sim {
namespace {

namespace fs = std::filesystem;

/// The slice's depth frames with their truth and colour image, paths absolute.
struct Slice {
  std::vector<tum::TimedFile> depth;
  std::vector<tum::TimedFile> rgb;
  std::vector<tum::TimedPose> truth;
  std::size_t dropped = 0;
};

std::string absolutePath(const fs::path& dir, const std::string& file) {
  return fs::absolute(dir / file).lexically_normal().string();
}

fs::path requireFile(const fs::path& path) {
  if (!fs::is_regular_file(path)) {
    throw InputError(path.string() + ": missing (a TUM RGB-D source needs depth.txt and " +
                     "groundtruth.txt)");
  }
  return path;
}

/// Frames [first, last] of depth.txt; last defaults to the final frame.
std::pair<std::size_t, std::size_t> sliceRange(const std::vector<tum::TimedFile>& depth,
                                               const DriftedSessionConfig& config,
                                               const fs::path& depth_list) {
  const std::size_t count = depth.size();
  const std::size_t last = config.last_frame.value_or(count == 0 ? 0 : count - 1);
  if (config.first_frame >= count) {
    throw InputError(depth_list.string() + ": first frame " + std::to_string(config.first_frame) +
                     " is beyond its " + std::to_string(count) + " frames");
  }
  if (last >= count) {
    throw InputError(depth_list.string() + ": last frame " + std::to_string(last) +
                     " is beyond its " + std::to_string(count) + " frames (0.." +
                     std::to_string(count - 1) + ")");
  }
  return {config.first_frame, last};
}

Slice readSlice(const fs::path& source, const DriftedSessionConfig& config) {
  const fs::path depth_list = requireFile(source / "depth.txt");
  const fs::path truth_list = requireFile(source / "groundtruth.txt");
  const std::vector<tum::TimedFile> depth = tum::readFileList(depth_list.string());
  const std::vector<tum::TimedPose> truth = tum::readTrajectory(truth_list.string());
  std::vector<tum::TimedFile> rgb;
  if (fs::is_regular_file(source / "rgb.txt"))
    rgb = tum::readFileList((source / "rgb.txt").string());
  const auto [first, last] = sliceRange(depth, config, depth_list);
  const std::vector<double> truth_times = tum::timestampsOf(truth);
  const std::vector<double> rgb_times = tum::timestampsOf(rgb);
  Slice slice;
  for (std::size_t i = first; i <= last; ++i) {
    const double t_s = depth[i].timestamp_s;
    const auto pose = tum::nearestWithin(truth_times, t_s, tum::kMaxTimeDifference_s);
    if (!pose) {
      ++slice.dropped;
      continue;
    }
    slice.depth.push_back({t_s, absolutePath(source, depth[i].file)});
    slice.truth.push_back({t_s, truth[*pose].T_W_C});
    const auto color = tum::nearestWithin(rgb_times, t_s, tum::kMaxTimeDifference_s);
    if (color) slice.rgb.push_back({t_s, absolutePath(source, rgb[*color].file)});
  }
  if (slice.depth.empty()) {
    throw InputError(source.string() + ": no frame of the slice " + std::to_string(first) + ".." +
                     std::to_string(last) + " has a groundtruth.txt pose within 20 ms");
  }
  return slice;
}

/// T_S_C = T_S_W * drifted T_W_C, at the truth's timestamps.
std::vector<tum::TimedPose> odometryOf(const Slice& slice, const Eigen::Isometry3d& T_W_S,
                                       const DriftedSessionConfig& config) {
  std::vector<Eigen::Isometry3d> T_W_C;
  for (const tum::TimedPose& pose : slice.truth) T_W_C.push_back(pose.T_W_C);
  const std::vector<Eigen::Isometry3d> T_S_C =
      posesInFrame(T_W_S.inverse(), addOdometryDrift(T_W_C, config.drift, config.seed));
  std::vector<tum::TimedPose> odometry;
  for (std::size_t i = 0; i < T_S_C.size(); ++i) {
    odometry.push_back({slice.truth[i].timestamp_s, T_S_C[i]});
  }
  return odometry;
}

void requireDistinctFolders(const fs::path& source, const fs::path& out) {
  std::error_code error;
  if (fs::exists(out) && fs::equivalent(source, out, error)) {
    throw InputError(out.string() + ": the output folder is the source folder (its " +
                     "groundtruth.txt would be overwritten)");
  }
}

void writeFolder(const fs::path& source, const fs::path& out, const Slice& slice,
                 const std::vector<tum::TimedPose>& odometry, const Eigen::Isometry3d& T_W_S) {
  fs::create_directories(out);
  const std::string from = "slice of " + fs::absolute(source).lexically_normal().string();
  writeTumFileList((out / "depth.txt").string(), slice.depth, {"depth images of the " + from});
  writeTumFileList((out / "rgb.txt").string(), slice.rgb, {"colour images of the " + from});
  writeTumTrajectory((out / "groundtruth.txt").string(), slice.truth,
                     {"truth of the " + from, "timestamp tx ty tz qx qy qz qw (camera-to-world)"});
  writeTumTrajectory((out / "odometry.txt").string(), odometry,
                     {"drifted odometry in the session frame S (odometry_frame.txt holds T_W_S)",
                      "timestamp tx ty tz qx qy qz qw (camera-to-S)"});
  writeOdometryFrame((out / "odometry_frame.txt").string(), T_W_S);
  if (fs::is_regular_file(source / "camera.yaml")) {
    writeFileAtomically((out / "camera.yaml").string(),
                        readFile((source / "camera.yaml").string()));
  }
}

}  // namespace

void DriftedSessionConfig::validate() const {
  if (last_frame && first_frame > *last_frame) {
    throw InputError("DriftedSessionConfig: first_frame " + std::to_string(first_frame) +
                     " is after last_frame " + std::to_string(*last_frame));
  }
  drift.validate();
  frame.validate();
}

DriftedSession writeDriftedSession(const std::string& source_dir, const std::string& out_dir,
                                   const DriftedSessionConfig& config) {
  config.validate();
  const fs::path source(source_dir), out(out_dir);
  if (!fs::is_directory(source)) throw InputError(source_dir + ": no such folder");
  requireDistinctFolders(source, out);
  const Slice slice = readSlice(source, config);
  DriftedSession result;
  if (config.offset) result.T_W_S = randomOdometryFrame(config.frame, config.seed);
  writeFolder(source, out, slice, odometryOf(slice, result.T_W_S, config), result.T_W_S);
  result.frames = slice.depth.size();
  result.frames_dropped = slice.dropped;
  return result;
}

}  // namespace strata::sim

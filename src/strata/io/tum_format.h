#pragma once
// The TUM RGB-D text formats: file lists (rgb.txt, depth.txt) and trajectories (groundtruth.txt).
// https://cvg.cit.tum.de/data/datasets/rgbd-dataset/file_formats
#include <Eigen/Geometry>
#include <istream>
#include <optional>
#include <string>
#include <vector>

namespace strata::tum {

/// Association tolerance between depth, colour and pose timestamps.
constexpr double kMaxTimeDifference_s = 0.02;

/// One line of rgb.txt / depth.txt: `timestamp filename` (filename relative to the folder).
struct TimedFile {
  double timestamp_s = 0.0;
  std::string file;
};

/// One line of groundtruth.txt: `timestamp tx ty tz qx qy qz qw`, camera-to-world.
struct TimedPose {
  double timestamp_s = 0.0;
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
};

/// Reads a file list, sorted by timestamp; '#' lines and blank lines skipped. Throws InputError
/// naming the file and line for a missing file, a file over kMaxTumTextFileBytes (256 MiB) or a
/// malformed line.
std::vector<TimedFile> readFileList(const std::string& path);
/// The same from a stream; `name` (a path) prefixes error messages.
std::vector<TimedFile> readFileList(std::istream& in, const std::string& name);

/// Reads a trajectory, sorted by timestamp. The quaternion is normalised. Throws InputError naming
/// the file and line for a malformed line, a non-finite value or a zero quaternion, or a file over
/// kMaxTumTextFileBytes.
std::vector<TimedPose> readTrajectory(const std::string& path);
/// The same from a stream; `name` (a path) prefixes error messages.
std::vector<TimedPose> readTrajectory(std::istream& in, const std::string& name);

/// The timestamps of a file list or a trajectory, in their order.
std::vector<double> timestampsOf(const std::vector<TimedFile>& files);
std::vector<double> timestampsOf(const std::vector<TimedPose>& poses);

/// Camera-to-world pose from tx ty tz qx qy qz qw (quaternion normalised; it must not be zero).
/// Returns nullopt for a zero or non-finite quaternion.
std::optional<Eigen::Isometry3d> poseFromTum(const double values[7]);

/// `tx ty tz qx qy qz qw` with 9 decimals.
std::string poseToTum(const Eigen::Isometry3d& T_W_C);

/// Index of the timestamp in `sorted_s` nearest to `t_s`, when it is within `max_difference_s`.
std::optional<std::size_t> nearestWithin(const std::vector<double>& sorted_s, double t_s,
                                         double max_difference_s);

}  // namespace strata::tum

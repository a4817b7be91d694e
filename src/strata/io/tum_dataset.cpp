#include "strata/io/internal/tum_dataset.h"

#include <filesystem>
#include <sstream>

#include "strata/core/error.h"
#include "strata/io/camera_model.h"
#include "strata/io/image_io.h"
#include "strata/io/tum_format.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

struct TumEntry {
  double timestamp_s = 0.0;
  std::string depth_path;
  std::string color_path;  // "" when no colour image is associated
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
};

struct Association {
  std::vector<TumEntry> entries;
  std::size_t without_pose = 0;
  std::size_t without_color = 0;
};

CameraModel tumDefaults() {
  CameraModel model;  // CameraIntrinsics defaults are the TUM ones
  model.depth_scale = 5000.0;
  model.source = "TUM defaults";
  return model;
}

Association associate(const fs::path& folder, const std::vector<tum::TimedFile>& depth,
                      const std::vector<tum::TimedFile>& rgb,
                      const std::vector<tum::TimedPose>& poses) {
  const std::vector<double> pose_times = tum::timestampsOf(poses);
  const std::vector<double> rgb_times = tum::timestampsOf(rgb);
  Association out;
  for (const tum::TimedFile& d : depth) {
    const auto pose = tum::nearestWithin(pose_times, d.timestamp_s, tum::kMaxTimeDifference_s);
    if (!pose) {
      ++out.without_pose;
      continue;
    }
    // NOTE: an absolute listed path replaces the folder (std::filesystem::operator/), so a list
    // may name images of another folder (strata drift writes such lists).
    TumEntry entry{d.timestamp_s, (folder / d.file).string(), "", poses[*pose].T_W_C};
    const auto color = tum::nearestWithin(rgb_times, d.timestamp_s, tum::kMaxTimeDifference_s);
    if (color) entry.color_path = (folder / rgb[*color].file).string();
    if (!color && !rgb.empty()) ++out.without_color;
    out.entries.push_back(std::move(entry));
  }
  return out;
}

void requireFilesExist(const std::vector<TumEntry>& entries, const fs::path& list) {
  for (const TumEntry& e : entries) {
    if (!fs::is_regular_file(e.depth_path)) {
      throw InputError(e.depth_path + ": depth image not found (listed in " + list.string() + ")");
    }
  }
}

std::string describeWarnings(const Association& a, std::size_t depth_count,
                             const fs::path& pose_list) {
  std::ostringstream out;
  if (a.without_pose > 0) {
    out << a.without_pose << " of " << depth_count << " depth frames dropped: no pose in "
        << pose_list.filename().string() << " within 20 ms\n";
  }
  if (a.without_color > 0) {
    out << a.without_color << " frames have no colour image within 20 ms\n";
  }
  return out.str();
}

class TumDataset : public Dataset {
 public:
  TumDataset(std::string folder, CameraModel model, Association association, std::string warnings)
      : folder_(std::move(folder)),
        model_(std::move(model)),
        decoder_(model_.depth_scale, model_.depth_invalid),
        entries_(std::move(association.entries)),
        warnings_(std::move(warnings)) {}

  std::string name() const override { return "TUM RGB-D '" + folder_ + "'"; }
  std::size_t size() const override { return entries_.size(); }
  CameraIntrinsics intrinsics() const override { return model_.intrinsics; }
  std::string warnings() const override { return warnings_; }

  FrameStamp stamp(std::size_t index) const override {
    if (index >= entries_.size()) return Dataset::stamp(index);  // load() names the error
    return {entries_[index].timestamp_s, entries_[index].T_W_C};
  }

  RgbdFrame load(std::size_t index) const override {
    if (index >= entries_.size()) {
      throw InputError(name() + ": frame index " + std::to_string(index) + " out of range (" +
                       std::to_string(entries_.size()) + " frames)");
    }
    const TumEntry& e = entries_[index];
    RgbdFrame frame;
    frame.timestamp_s = e.timestamp_s;
    frame.name = e.depth_path;
    frame.T_W_C = e.T_W_C;
    frame.depth = readDepthPng(e.depth_path, decoder_);
    if (!e.color_path.empty()) frame.color = readColorImage(e.color_path);
    validateFrame(frame, model_.intrinsics);
    return frame;
  }

 private:
  std::string folder_;
  CameraModel model_;
  DepthDecoder decoder_;
  std::vector<TumEntry> entries_;
  std::string warnings_;
};

}  // namespace

std::unique_ptr<Dataset> openTumDataset(const std::string& folder, const DatasetOptions& options) {
  const fs::path dir(folder);
  const fs::path depth_list = dir / "depth.txt";
  const fs::path rgb_list = dir / "rgb.txt";
  const bool overridden = !options.trajectory_file.empty();
  const fs::path pose_list =
      overridden ? fs::path(options.trajectory_file) : dir / "groundtruth.txt";
  if (!fs::is_regular_file(depth_list)) {
    throw InputError(depth_list.string() + ": missing (a TUM RGB-D folder needs depth.txt)");
  }
  if (!fs::is_regular_file(pose_list)) {
    throw InputError(pose_list.string() +
                     (overridden ? ": trajectory file not found"
                                 : ": missing (a TUM RGB-D folder needs groundtruth.txt)"));
  }
  CameraModel model = resolveCameraModel(folder, options, tumDefaults());
  const std::vector<tum::TimedFile> depth = tum::readFileList(depth_list.string());
  std::vector<tum::TimedFile> rgb;
  if (options.load_color && fs::is_regular_file(rgb_list))
    rgb = tum::readFileList(rgb_list.string());
  Association association = associate(dir, depth, rgb, tum::readTrajectory(pose_list.string()));
  if (association.entries.empty()) {
    throw InputError(folder + ": no frames: depth.txt lists " + std::to_string(depth.size()) +
                     " depth image(s), none with a pose in " + pose_list.string() +
                     " within 20 ms");
  }
  requireFilesExist(association.entries, depth_list);
  std::string warnings = describeWarnings(association, depth.size(), pose_list);
  return std::make_unique<TumDataset>(folder, std::move(model), std::move(association),
                                      std::move(warnings));
}

}  // namespace strata

#include "strata/io/seven_scenes_dataset.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "strata/core/error.h"
#include "strata/core/file_limits.h"
#include "strata/io/camera_model.h"
#include "strata/io/image_io.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

constexpr const char* kDepthSuffix = ".depth.png";
constexpr double kFrameRate_hz = 30.0;
// Checked before a pose file is read: 16 numbers take a few hundred bytes; 64 KiB allows comments.
constexpr FileSizeLimit kMaxPoseFileBytes{"kMaxPoseFileBytes", std::uint64_t{64} << 10};

bool endsWith(const std::string& text, const std::string& suffix) {
  return text.size() >= suffix.size() &&
         text.compare(text.size() - suffix.size(), suffix.size(), suffix) == 0;
}

/// "frame-000000" for every frame-000000.depth.png in the folder, sorted.
std::vector<std::string> frameStems(const fs::path& folder) {
  std::vector<std::string> stems;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const std::string file = entry.path().filename().string();
    if (file.rfind("frame-", 0) == 0 && endsWith(file, kDepthSuffix)) {
      stems.push_back(file.substr(0, file.size() - std::string(kDepthSuffix).size()));
    }
  }
  std::sort(stems.begin(), stems.end());
  return stems;
}

CameraModel sevenScenesDefaults(const fs::path& folder) {
  CameraModel model;
  model.intrinsics.fx_px = 585.0f;
  model.intrinsics.fy_px = 585.0f;
  model.intrinsics.cx_px = 320.0f;
  model.intrinsics.cy_px = 240.0f;
  model.depth_scale = 1000.0;
  model.depth_invalid = {0, 65535};
  model.source = "7-Scenes defaults";
  // camera.yaml, applied later by resolveCameraModel, overrides these keys where it has them.
  const fs::path k_file = folder / "camera-intrinsics.txt";
  if (fs::is_regular_file(k_file)) applyIntrinsicsMatrixFile(k_file.string(), &model);
  return model;
}

class SevenScenesDataset : public Dataset {
 public:
  SevenScenesDataset(fs::path folder, CameraModel model, std::vector<std::string> stems,
                     bool load_color)
      : folder_(std::move(folder)),
        model_(std::move(model)),
        decoder_(model_.depth_scale, model_.depth_invalid),
        stems_(std::move(stems)),
        load_color_(load_color) {}

  std::string name() const override { return "7-Scenes '" + folder_.string() + "'"; }
  std::size_t size() const override { return stems_.size(); }
  CameraIntrinsics intrinsics() const override { return model_.intrinsics; }

  RgbdFrame load(std::size_t index) const override {
    if (index >= stems_.size()) {
      throw InputError(name() + ": frame index " + std::to_string(index) + " out of range (" +
                       std::to_string(stems_.size()) + " frames)");
    }
    const std::string base = (folder_ / stems_[index]).string();
    RgbdFrame frame;
    frame.timestamp_s = static_cast<double>(index) / kFrameRate_hz;
    frame.name = base + kDepthSuffix;
    frame.depth = readDepthPng(frame.name, decoder_);
    frame.T_W_C = readPoseMatrixFile(base + ".pose.txt");
    if (load_color_ && fs::is_regular_file(base + ".color.jpg")) {
      frame.color = readColorImage(base + ".color.jpg");
    }
    validateFrame(frame, model_.intrinsics);
    return frame;
  }

 private:
  fs::path folder_;
  CameraModel model_;
  DepthDecoder decoder_;
  std::vector<std::string> stems_;
  bool load_color_;
};

Eigen::Matrix3d nearestRotation(const Eigen::Matrix3d& m) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();  // det > 0 since validatePose checked it
}

}  // namespace

bool looksLike7Scenes(const std::string& folder) {
  return fs::is_directory(folder) && !frameStems(folder).empty();
}

Eigen::Isometry3d readPoseMatrixFile(const std::string& path) {
  checkFileSize(path, kMaxPoseFileBytes, "pose file");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": pose file not found or not readable");
  return readPoseMatrix(in, path);
}

Eigen::Isometry3d readPoseMatrix(std::istream& in, const std::string& path) {
  Eigen::Matrix4d m;
  for (int i = 0; i < 16; ++i) {
    std::string token;
    char* end = nullptr;
    if (!(in >> token)) throw InputError(path + ": expected a 4x4 matrix of 16 numbers");
    m(i / 4, i % 4) = std::strtod(token.c_str(), &end);
    if (end == token.c_str() || *end != '\0') {
      throw InputError(path + ": '" + token + "' is not a number (expected a 4x4 matrix)");
    }
    if (!std::isfinite(m(i / 4, i % 4))) {
      throw InputError(path + ": pose has non-finite value '" + token + "'");
    }
  }
  if ((m.row(3) - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-6) {
    throw InputError(path + ": last row of the 4x4 pose is not 0 0 0 1");
  }
  Eigen::Isometry3d T_W_C;
  T_W_C.matrix() = m;
  validatePose(T_W_C, path);
  // NOTE: 7-Scenes rotations are orthonormal only to ~2e-4 (KinectFusion in float); use the nearest
  // rotation so Isometry3d::inverse() (a transpose) is exact.
  T_W_C.linear() = nearestRotation(T_W_C.linear());
  return T_W_C;
}

std::unique_ptr<Dataset> open7ScenesDataset(const std::string& folder,
                                            const DatasetOptions& options) {
  if (!options.trajectory_file.empty()) {
    throw InputError(folder + ": a trajectory file (" + options.trajectory_file +
                     ") overrides poses of TUM RGB-D folders only; 7-Scenes poses are per-frame "
                     "files");
  }
  const fs::path dir(folder);
  std::vector<std::string> stems = frameStems(dir);
  if (stems.empty()) throw InputError(folder + ": no frame-*.depth.png images (7-Scenes layout)");
  for (const std::string& stem : stems) {
    const fs::path pose = dir / (stem + ".pose.txt");
    if (!fs::is_regular_file(pose)) {
      throw InputError(pose.string() + ": pose file missing for " + stem + kDepthSuffix);
    }
  }
  CameraModel model = resolveCameraModel(folder, options, sevenScenesDefaults(dir));
  return std::make_unique<SevenScenesDataset>(dir, std::move(model), std::move(stems),
                                              options.load_color);
}

}  // namespace strata

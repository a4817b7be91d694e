#include "strata/io/tum_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/io/image_io.h"
#include "strata/io/tum_format.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

std::string timestampText(double timestamp_s, int decimals = 6) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.*f", decimals, timestamp_s);
  return text;
}

std::string cameraYaml(const CameraIntrinsics& k, double depth_scale) {
  std::ostringstream out;
  out.precision(9);
  out << "# written by strata::writeTumDataset\n"
      << "width: " << k.width_px << "\nheight: " << k.height_px << "\nfx: " << k.fx_px
      << "\nfy: " << k.fy_px << "\ncx: " << k.cx_px << "\ncy: " << k.cy_px
      << "\ndepth_scale: " << depth_scale << "   # PNG value per metre\ndepth_invalid: [0]\n";
  return out.str();
}

std::string commentText(const std::vector<std::string>& comment) {
  std::string text;
  for (const std::string& line : comment) text += "# " + line + "\n";
  return text;
}

}  // namespace

void writeTumTrajectory(const std::string& path, const std::vector<tum::TimedPose>& poses,
                        const std::vector<std::string>& comment, int timestamp_decimals) {
  if (timestamp_decimals < 0 || timestamp_decimals > 9) {
    throw InputError(path + ": a trajectory's timestamps take 0 to 9 decimals, not " +
                     std::to_string(timestamp_decimals));
  }
  std::string text = commentText(comment);
  for (const tum::TimedPose& pose : poses) {
    text += timestampText(pose.timestamp_s, timestamp_decimals) + " " + tum::poseToTum(pose.T_W_C) + "\n";
  }
  writeTextAtomically(path, text);
}

void writeTumFileList(const std::string& path, const std::vector<tum::TimedFile>& files,
                      const std::vector<std::string>& comment) {
  std::string text = commentText(comment);
  for (const tum::TimedFile& file : files) {
    if (file.file.find_first_of(" \t\r\n") != std::string::npos) {
      throw InputError(path + ": cannot list '" + file.file +
                       "': TUM file lists cannot hold a name with whitespace");
    }
    text += timestampText(file.timestamp_s) + " " + file.file + "\n";
  }
  writeTextAtomically(path, text);
}

TumWriter::TumWriter(const std::string& dir, const CameraIntrinsics& intrinsics,
                     double depth_scale)
    : dir_(dir), intrinsics_(intrinsics), depth_scale_(depth_scale) {
  if (!std::isfinite(depth_scale) || depth_scale <= 0.0) {
    throw InputError("writeTumDataset: depth_scale must be finite and positive");
  }
  intrinsics_.validate();
  std::error_code ec;
  fs::create_directories(fs::path(dir) / "depth", ec);
  fs::create_directories(fs::path(dir) / "rgb", ec);
  if (ec) throw Error(dir + ": cannot create folder: " + ec.message());
  const std::string header = "# written by strata::writeTumDataset\n";
  depth_list_ = rgb_list_ = header;
  poses_ = header + "# timestamp tx ty tz qx qy qz qw (camera-to-world)\n";
}

void TumWriter::add(const RgbdFrame& frame) {
  validateFrame(frame, intrinsics_);
  // NOTE: 1 us, the resolution of the written timestamps.
  if (count_ > 0 && !(frame.timestamp_s >= last_timestamp_s_ + 1e-6)) {
    std::ostringstream msg;
    msg << "writeTumDataset: frame " << count_ << " timestamp " << frame.timestamp_s
        << " s does not increase after " << last_timestamp_s_ << " s";
    throw InputError(msg.str());
  }
  char stem[32];
  std::snprintf(stem, sizeof(stem), "%06zu.png", count_);
  const std::string stamp = timestampText(frame.timestamp_s);
  const fs::path root(dir_);
  writeDepthPng((root / "depth" / stem).string(), frame.depth, depth_scale_);
  depth_list_ += stamp + " depth/" + stem + "\n";
  if (!frame.color.empty()) {
    writeColorPng((root / "rgb" / stem).string(), frame.color);
    rgb_list_ += stamp + " rgb/" + stem + "\n";
  }
  poses_ += stamp + " " + tum::poseToTum(frame.T_W_C) + "\n";
  last_timestamp_s_ = frame.timestamp_s;
  ++count_;
}

void TumWriter::finish() {
  const fs::path root(dir_);
  writeTextAtomically(root / "depth.txt", depth_list_);
  writeTextAtomically(root / "rgb.txt", rgb_list_);
  writeTextAtomically(root / "groundtruth.txt", poses_);
  writeTextAtomically(root / "camera.yaml", cameraYaml(intrinsics_, depth_scale_));
}

void writeTumDataset(const std::string& dir, const CameraIntrinsics& intrinsics,
                     const std::vector<RgbdFrame>& frames, double depth_scale) {
  TumWriter writer(dir, intrinsics, depth_scale);
  for (const RgbdFrame& frame : frames) writer.add(frame);
  writer.finish();
}

}  // namespace strata

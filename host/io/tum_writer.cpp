#include "io/tum_writer.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "io/image_io.h"
#include "io/tum_format.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

std::ofstream openText(const fs::path& path) {
  std::ofstream out(path);
  if (!out) throw Error(path.string() + ": cannot create file");
  out << "# written by strata::writeTumDataset\n";
  return out;
}

std::string timestampText(double timestamp_s) {
  char text[64];
  std::snprintf(text, sizeof(text), "%.6f", timestamp_s);
  return text;
}

void checkFrames(const CameraIntrinsics& intrinsics, const std::vector<RgbdFrame>& frames) {
  intrinsics.validate();
  for (std::size_t i = 0; i < frames.size(); ++i) {
    validateFrame(frames[i], intrinsics);
    // NOTE: 1 us, the resolution of the written timestamps.
    if (i > 0 && !(frames[i].timestamp_s >= frames[i - 1].timestamp_s + 1e-6)) {
      std::ostringstream msg;
      msg << "writeTumDataset: frame " << i << " timestamp " << frames[i].timestamp_s
          << " s does not increase after " << frames[i - 1].timestamp_s << " s";
      throw InputError(msg.str());
    }
  }
}

void writeCameraYaml(const fs::path& path, const CameraIntrinsics& k, double depth_scale) {
  std::ofstream out(path);
  if (!out) throw Error(path.string() + ": cannot create file");
  out.precision(9);
  out << "# written by strata::writeTumDataset\n"
      << "width: " << k.width_px << "\nheight: " << k.height_px << "\nfx: " << k.fx_px
      << "\nfy: " << k.fy_px << "\ncx: " << k.cx_px << "\ncy: " << k.cy_px
      << "\ndepth_scale: " << depth_scale << "   # PNG value per metre\ndepth_invalid: [0]\n";
}

}  // namespace

void writeTumDataset(const std::string& dir, const CameraIntrinsics& intrinsics,
                     const std::vector<RgbdFrame>& frames, double depth_scale) {
  if (!std::isfinite(depth_scale) || depth_scale <= 0.0) {
    throw InputError("writeTumDataset: depth_scale must be finite and positive");
  }
  checkFrames(intrinsics, frames);
  const fs::path root(dir);
  std::error_code ec;
  fs::create_directories(root / "depth", ec);
  fs::create_directories(root / "rgb", ec);
  if (ec) throw Error(dir + ": cannot create folder: " + ec.message());

  std::ofstream depth_list = openText(root / "depth.txt");
  std::ofstream rgb_list = openText(root / "rgb.txt");
  std::ofstream poses = openText(root / "groundtruth.txt");
  poses << "# timestamp tx ty tz qx qy qz qw (camera-to-world)\n";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    char stem[32];
    std::snprintf(stem, sizeof(stem), "%06zu.png", i);
    const std::string stamp = timestampText(frames[i].timestamp_s);
    writeDepthPng((root / "depth" / stem).string(), frames[i].depth, depth_scale);
    depth_list << stamp << " depth/" << stem << "\n";
    if (!frames[i].color.empty()) {
      writeColorPng((root / "rgb" / stem).string(), frames[i].color);
      rgb_list << stamp << " rgb/" << stem << "\n";
    }
    poses << stamp << " " << tum::poseToTum(frames[i].T_W_C) << "\n";
  }
  writeCameraYaml(root / "camera.yaml", intrinsics, depth_scale);
  depth_list.close();
  rgb_list.close();
  poses.close();
  if (!depth_list || !rgb_list || !poses) throw Error(dir + ": error while writing the lists");
}

}  // namespace strata

#pragma once
// Basic sensor types shared by the engine and the host side.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

namespace strata {

/// Pinhole intrinsics of a depth camera, pixels. Pixel centres sit at integer coordinates.
struct CameraIntrinsics {
  int width_px = 640;
  int height_px = 480;
  float fx_px = 525.0f;
  float fy_px = 525.0f;
  float cx_px = 319.5f;
  float cy_px = 239.5f;

  /// Throws InputError naming the bad field (zero/negative/non-finite focal length, empty size...).
  void validate() const;
};

/// Depth in metres, row-major; 0 marks an invalid pixel (NaN is tolerated and also ignored).
struct DepthImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<float> depth_m;

  DepthImage() = default;
  DepthImage(int width, int height, float fill = 0.0f)
      : width_px(width), height_px(height), depth_m(static_cast<size_t>(width) * height, fill) {}
  float at(int u, int v) const { return depth_m[static_cast<size_t>(v) * width_px + u]; }
  float& at(int u, int v) { return depth_m[static_cast<size_t>(v) * width_px + u]; }
  bool empty() const { return depth_m.empty(); }
};

/// 8-bit RGB, row-major, 3 bytes per pixel.
struct ColorImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<std::uint8_t> rgb;

  ColorImage() = default;
  ColorImage(int width, int height, std::uint8_t fill = 0)
      : width_px(width), height_px(height), rgb(static_cast<size_t>(width) * height * 3, fill) {}
  bool empty() const { return rgb.empty(); }
};

/// 8-bit luminance, row-major, one byte per pixel (grey cameras: EuRoC, the simulator's).
struct GreyImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<std::uint8_t> pixels;

  GreyImage() = default;
  GreyImage(int width, int height, std::uint8_t fill = 0)
      : width_px(width), height_px(height), pixels(static_cast<size_t>(width) * height, fill) {}
  std::uint8_t at(int u, int v) const { return pixels[static_cast<size_t>(v) * width_px + u]; }
  bool empty() const { return pixels.empty(); }
};

/// One RGB-D frame with the camera-to-world pose. Colour may be empty.
struct RgbdFrame {
  double timestamp_s = 0.0;
  std::string name;  // for messages: file name or index
  DepthImage depth;
  ColorImage color;
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
};

/// Throws InputError when the pose has a non-finite entry or a rotation that is not orthonormal.
void validatePose(const Eigen::Isometry3d& T_W_C, const std::string& what);

/// Throws InputError when depth/colour sizes disagree with the intrinsics.
void validateFrame(const RgbdFrame& frame, const CameraIntrinsics& intrinsics);

}  // namespace strata

#pragma once
// PNG/JPEG reading and writing for depth, colour and grey images (OpenCV underneath, not exposed).
#include <cstdint>
#include <string>
#include <vector>

#include "strata/core/types.h"

namespace strata {

/// Turns raw 16-bit depth PNG values into metres: value / depth_scale, 0 for invalid values.
/// Thread safe (immutable after construction).
class DepthDecoder {
 public:
  /// `depth_invalid` lists raw values that mean "no measurement" (0 should be among them).
  DepthDecoder(double depth_scale, const std::vector<std::uint16_t>& depth_invalid);
  float metres(std::uint16_t raw) const { return lut_m_[raw]; }
  double depthScale() const { return depth_scale_; }

 private:
  double depth_scale_;
  std::vector<float> lut_m_;  // 65536 entries
};

/// Reads a 16-bit single-channel depth PNG. Throws InputError naming the file when it is missing,
/// unreadable, of another type (e.g. 8-bit or 3-channel), over kMaxImageFileBytes (256 MiB), or its
/// header claims a size over core/image_limits.h (refused before decoding).
DepthImage readDepthPng(const std::string& path, const DepthDecoder& decoder);
/// The same from the file's bytes; `name` (a path) prefixes error messages.
DepthImage decodeDepthPng(const std::vector<std::uint8_t>& bytes, const std::string& name,
                          const DepthDecoder& decoder);

/// Reads a PNG or JPEG colour image as RGB (other formats are refused: their sizes are not checked
/// before decoding). Throws InputError naming the file, with the same limits as readDepthPng.
ColorImage readColorImage(const std::string& path);
/// The same from the file's bytes; `name` (a path) prefixes error messages.
ColorImage decodeColorImage(const std::vector<std::uint8_t>& bytes, const std::string& name);

/// Reads an 8-bit single-channel PNG or JPEG (EuRoC cameras). Other types (colour, 16-bit) are
/// refused, not converted. Throws InputError naming the file, with the same limits as readDepthPng.
GreyImage readGreyImage(const std::string& path);
/// The same from the file's bytes; `name` (a path) prefixes error messages.
GreyImage decodeGreyImage(const std::vector<std::uint8_t>& bytes, const std::string& name);

/// Writes depth as a 16-bit PNG: round(depth_m * depth_scale); 0 and non-finite stay 0. Throws
/// InputError when a depth does not fit 16 bits at that scale, Error when the file cannot be
/// written.
void writeDepthPng(const std::string& path, const DepthImage& depth, double depth_scale);

/// Writes an RGB image as PNG. Throws Error when the file cannot be written.
void writeColorPng(const std::string& path, const ColorImage& color);

/// Writes an 8-bit grey PNG, atomically. Throws Error when the file cannot be written.
void writeGreyPng(const std::string& path, const GreyImage& grey);

}  // namespace strata

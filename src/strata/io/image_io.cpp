#include "strata/io/image_io.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/file_limits.h"
#include "strata/io/internal/image_header.h"

namespace strata {
namespace {

std::string describeType(const cv::Mat& image) {
  const int depth = image.depth();
  const char* bits = depth == CV_8U    ? "8-bit"
                     : depth == CV_16U ? "16-bit"
                     : depth == CV_32F ? "32-bit float"
                                       : "non-integer";
  std::ostringstream out;
  out << bits << " " << image.channels() << "-channel";
  return out.str();
}

// Checked before an image file is read: an 8192 x 8192 16-bit PNG stored uncompressed is 128 MiB.
constexpr FileSizeLimit kMaxImageFileBytes{"kMaxImageFileBytes", std::uint64_t{256} << 20};

/// Decodes PNG or JPEG bytes after their header passed the size limits.
cv::Mat decodeImage(const std::vector<std::uint8_t>& bytes, const std::string& name, int flags,
                    const char* what) {
  const detail::ImageHeader header = detail::readImageHeader(bytes, name + ": " + what);
  detail::checkImageHeader(header, bytes.size(), name + ": " + what);
  cv::Mat image;
  try {
    image = cv::imdecode(bytes, flags);
  } catch (const cv::Exception& e) {
    throw InputError(name + ": cannot decode " + what + ": " + e.what());
  }
  if (image.empty())
    throw InputError(name + ": cannot decode " + what + " (corrupt or not an image)");
  return image;
}

/// Encodes by the file's extension, then writes atomically (a reader never sees half a PNG).
void writeImage(const std::string& path, const cv::Mat& image) {
  const std::size_t dot = path.find_last_of('.');
  const std::string extension = dot == std::string::npos ? ".png" : path.substr(dot);
  std::vector<std::uint8_t> encoded;
  bool ok = false;
  try {
    ok = cv::imencode(extension, image, encoded);
  } catch (const cv::Exception& e) {
    throw Error(path + ": cannot encode image: " + e.what());
  }
  if (!ok) throw Error(path + ": cannot encode image as '" + extension + "'");
  writeFileAtomically(path, encoded);
}

}  // namespace

DepthDecoder::DepthDecoder(double depth_scale, const std::vector<std::uint16_t>& depth_invalid)
    : depth_scale_(depth_scale), lut_m_(65536) {
  for (std::size_t raw = 0; raw < lut_m_.size(); ++raw) {
    lut_m_[raw] = static_cast<float>(static_cast<double>(raw) / depth_scale);
  }
  for (std::uint16_t raw : depth_invalid) lut_m_[raw] = 0.0f;
}

DepthImage readDepthPng(const std::string& path, const DepthDecoder& decoder) {
  return decodeDepthPng(readFileBounded(path, kMaxImageFileBytes, "depth image"), path, decoder);
}

DepthImage decodeDepthPng(const std::vector<std::uint8_t>& bytes, const std::string& path,
                          const DepthDecoder& decoder) {
  // NOTE: IMREAD_UNCHANGED (keeps bit depth like IMREAD_ANYDEPTH, and also the channel count) so a
  // 3-channel 16-bit file is reported instead of silently converted to grey.
  const cv::Mat raw = decodeImage(bytes, path, cv::IMREAD_UNCHANGED, "depth image");
  if (raw.type() != CV_16UC1) {
    throw InputError(path + ": depth image must be 16-bit single-channel, found " +
                     describeType(raw));
  }
  DepthImage depth(raw.cols, raw.rows);
  for (int v = 0; v < raw.rows; ++v) {
    const std::uint16_t* row = raw.ptr<std::uint16_t>(v);
    for (int u = 0; u < raw.cols; ++u) depth.at(u, v) = decoder.metres(row[u]);
  }
  return depth;
}

ColorImage readColorImage(const std::string& path) {
  return decodeColorImage(readFileBounded(path, kMaxImageFileBytes, "colour image"), path);
}

ColorImage decodeColorImage(const std::vector<std::uint8_t>& bytes, const std::string& path) {
  const cv::Mat bgr = decodeImage(bytes, path, cv::IMREAD_COLOR, "colour image");
  ColorImage color(bgr.cols, bgr.rows);
  for (int v = 0; v < bgr.rows; ++v) {
    const cv::Vec3b* row = bgr.ptr<cv::Vec3b>(v);
    std::uint8_t* out = color.rgb.data() + static_cast<std::size_t>(v) * bgr.cols * 3;
    for (int u = 0; u < bgr.cols; ++u, out += 3) {
      out[0] = row[u][2];
      out[1] = row[u][1];
      out[2] = row[u][0];
    }
  }
  return color;
}

GreyImage readGreyImage(const std::string& path) {
  return decodeGreyImage(readFileBounded(path, kMaxImageFileBytes, "grey image"), path);
}

GreyImage decodeGreyImage(const std::vector<std::uint8_t>& bytes, const std::string& path) {
  // NOTE: IMREAD_UNCHANGED so a colour or 16-bit file is reported, not silently converted.
  const cv::Mat raw = decodeImage(bytes, path, cv::IMREAD_UNCHANGED, "grey image");
  if (raw.type() != CV_8UC1) {
    throw InputError(path + ": grey image must be 8-bit single-channel, found " +
                     describeType(raw));
  }
  GreyImage grey(raw.cols, raw.rows);
  for (int v = 0; v < raw.rows; ++v) {
    const std::uint8_t* row = raw.ptr<std::uint8_t>(v);
    std::copy(row, row + raw.cols, grey.pixels.data() + static_cast<std::size_t>(v) * raw.cols);
  }
  return grey;
}

void writeDepthPng(const std::string& path, const DepthImage& depth, double depth_scale) {
  cv::Mat raw(depth.height_px, depth.width_px, CV_16UC1);
  for (int v = 0; v < depth.height_px; ++v) {
    std::uint16_t* row = raw.ptr<std::uint16_t>(v);
    for (int u = 0; u < depth.width_px; ++u) {
      const float d = depth.at(u, v);
      const double value = std::isfinite(d) && d > 0.0f ? std::round(d * depth_scale) : 0.0;
      if (value > 65535.0) {
        std::ostringstream msg;
        msg << path << ": depth " << d << " m at pixel (" << u << ", " << v
            << ") does not fit a 16-bit PNG at depth_scale " << depth_scale;
        throw InputError(msg.str());
      }
      row[u] = static_cast<std::uint16_t>(value);
    }
  }
  writeImage(path, raw);
}

void writeColorPng(const std::string& path, const ColorImage& color) {
  cv::Mat bgr(color.height_px, color.width_px, CV_8UC3);
  for (int v = 0; v < color.height_px; ++v) {
    const std::uint8_t* in = color.rgb.data() + static_cast<std::size_t>(v) * color.width_px * 3;
    cv::Vec3b* row = bgr.ptr<cv::Vec3b>(v);
    for (int u = 0; u < color.width_px; ++u, in += 3) row[u] = cv::Vec3b(in[2], in[1], in[0]);
  }
  writeImage(path, bgr);
}

void writeGreyPng(const std::string& path, const GreyImage& grey) {
  if (grey.pixels.size() != static_cast<std::size_t>(grey.width_px) * grey.height_px) {
    throw InputError(path + ": grey image has " + std::to_string(grey.pixels.size()) +
                     " pixels for " + std::to_string(grey.width_px) + "x" +
                     std::to_string(grey.height_px));
  }
  // The Mat wraps the pixels without copying; imencode only reads them.
  const cv::Mat raw(grey.height_px, grey.width_px, CV_8UC1,
                    const_cast<std::uint8_t*>(grey.pixels.data()));
  writeImage(path, raw);
}

}  // namespace strata

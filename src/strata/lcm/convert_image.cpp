#include "strata/lcm/convert_image.h"

#include <cmath>
#include <cstring>

#include "strata/core/error.h"

namespace strata::lcm_io {
namespace {

int bytesPerPixel(const std::string& encoding) {
  if (encoding == kDepth16) return 2;
  if (encoding == kDepth32f) return 4;
  if (encoding == kRgb8 || encoding == kBgr8) return 3;
  if (encoding == kMono8) return 1;
  return 0;
}

/// Checks sizes against the payload; returns the pixel count.
std::size_t checkedPixels(const image_t& image, const char* what) {
  const int bpp = bytesPerPixel(image.encoding);
  if (bpp == 0) {
    throw InputError(std::string(what) + " image: unknown encoding '" + image.encoding +
                     "' (expected depth16, depth32f, rgb8, bgr8 or mono8)");
  }
  checkImageSize(image.width, image.height, std::string(what) + " image");
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  const std::size_t expected = pixels * static_cast<std::size_t>(bpp);
  if (image.size < 0 || static_cast<std::size_t>(image.size) != expected ||
      image.data.size() != expected) {
    throw InputError(std::string(what) + " image: " + std::to_string(image.data.size()) +
                     " bytes of " + image.encoding + " data for " + std::to_string(image.width) +
                     "x" + std::to_string(image.height) + " pixels (expected " +
                     std::to_string(expected) + ")");
  }
  return pixels;
}

}  // namespace

DepthImage decodeDepth(const image_t& image) {
  if (image.encoding != kDepth16 && image.encoding != kDepth32f) {
    throw InputError("depth image: encoding '" + image.encoding +
                     "' is not a depth encoding (depth16 or depth32f)");
  }
  const std::size_t pixels = checkedPixels(image, "depth");
  DepthImage depth(image.width, image.height);
  if (image.encoding == kDepth32f) {
    std::memcpy(depth.depth_m.data(), image.data.data(), pixels * sizeof(float));
    return depth;
  }
  if (!std::isfinite(image.depth_scale) || image.depth_scale <= 0.0f) {
    throw InputError("depth image: depth16 needs a positive finite depth_scale (units per metre)");
  }
  for (std::size_t i = 0; i < pixels; ++i) {
    const unsigned raw = image.data[2 * i] | (static_cast<unsigned>(image.data[2 * i + 1]) << 8);
    // NOTE: the same arithmetic as the PNG readers (io/image_io.cpp), so depth sent as depth16
    // decodes to the very floats a dataset reader gives.
    depth.depth_m[i] = static_cast<float>(static_cast<double>(raw) / image.depth_scale);
  }
  return depth;
}

ColorImage decodeColor(const image_t& image) {
  if (image.encoding.empty()) {
    if (image.size != 0 || !image.data.empty()) {
      throw InputError("colour image: no encoding but " + std::to_string(image.data.size()) +
                       " bytes of data");
    }
    return {};
  }
  if (image.encoding != kRgb8 && image.encoding != kBgr8 && image.encoding != kMono8) {
    throw InputError("colour image: encoding '" + image.encoding +
                     "' is not a colour encoding (rgb8, bgr8 or mono8)");
  }
  const std::size_t pixels = checkedPixels(image, "colour");
  ColorImage color(image.width, image.height);
  for (std::size_t i = 0; i < pixels; ++i) {
    std::uint8_t* out = &color.rgb[3 * i];
    if (image.encoding == kMono8) {
      out[0] = out[1] = out[2] = image.data[i];
    } else if (image.encoding == kBgr8) {
      out[0] = image.data[3 * i + 2];
      out[1] = image.data[3 * i + 1];
      out[2] = image.data[3 * i];
    } else {
      std::memcpy(out, &image.data[3 * i], 3);
    }
  }
  return color;
}

image_t encodeDepth16(const DepthImage& depth, float depth_scale, std::int64_t utime) {
  image_t image{};
  image.utime = utime;
  image.encoding = kDepth16;
  image.width = depth.width_px;
  image.height = depth.height_px;
  image.depth_scale = depth_scale;
  image.data.resize(depth.depth_m.size() * 2);
  for (std::size_t i = 0; i < depth.depth_m.size(); ++i) {
    const float units = depth.depth_m[i] * depth_scale;
    const long raw =
        std::isfinite(units) && units > 0.0f && units <= 65535.0f ? std::lround(units) : 0;
    image.data[2 * i] = static_cast<std::uint8_t>(raw & 0xFF);
    image.data[2 * i + 1] = static_cast<std::uint8_t>(raw >> 8);
  }
  image.size = static_cast<std::int32_t>(image.data.size());
  return image;
}

image_t encodeDepth32f(const DepthImage& depth, std::int64_t utime) {
  image_t image{};
  image.utime = utime;
  image.encoding = kDepth32f;
  image.width = depth.width_px;
  image.height = depth.height_px;
  image.depth_scale = 1.0f;
  image.data.resize(depth.depth_m.size() * sizeof(float));
  std::memcpy(image.data.data(), depth.depth_m.data(), image.data.size());
  image.size = static_cast<std::int32_t>(image.data.size());
  return image;
}

image_t encodeColor(const ColorImage& color, std::int64_t utime) {
  image_t image{};
  image.utime = utime;
  image.depth_scale = 0.0f;
  if (color.empty()) return image;  // encoding "", size 0
  image.encoding = kRgb8;
  image.width = color.width_px;
  image.height = color.height_px;
  image.data = color.rgb;
  image.size = static_cast<std::int32_t>(image.data.size());
  return image;
}

}  // namespace strata::lcm_io

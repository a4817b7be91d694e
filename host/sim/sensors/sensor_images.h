#pragma once
// Images the simulated sensors produce beside core/types.h's DepthImage and ColorImage.
#include <cstdint>
#include <vector>

#include "sim/ray_scene.h"

namespace strata::sim {

/// Per-pixel object id, row-major: kStaticObjectId (0) for static structure, 1, 2, ... for
/// movable objects, kNoHitObjectId (-1) where the ray hit nothing.
struct ObjectIdImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<std::int32_t> ids;

  ObjectIdImage() = default;
  ObjectIdImage(int width, int height)
      : width_px(width),
        height_px(height),
        ids(static_cast<std::size_t>(width) * height, kNoHitObjectId) {}
  std::int32_t at(int u, int v) const { return ids[static_cast<std::size_t>(v) * width_px + u]; }
};

/// 8-bit luminance, row-major, one byte per pixel.
struct GreyImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<std::uint8_t> pixels;

  GreyImage() = default;
  GreyImage(int width, int height)
      : width_px(width), height_px(height), pixels(static_cast<std::size_t>(width) * height, 0) {}
  std::uint8_t at(int u, int v) const { return pixels[static_cast<std::size_t>(v) * width_px + u]; }
};

}  // namespace strata::sim

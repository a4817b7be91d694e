#pragma once
// Images the simulated sensors produce beside core/types.h's DepthImage and ColorImage.
#include <cstdint>
#include <vector>

#include "strata/core/types.h"
#include "strata/sim/ray_scene.h"

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

/// The grey image type lives in core/types.h so dataset readers (io) share it with the simulator.
using GreyImage = ::strata::GreyImage;

}  // namespace strata::sim

#include "strata/core/image_limits.h"

#include "strata/core/error.h"

namespace strata {

void checkImageSize(long long width_px, long long height_px, const std::string& what) {
  const std::string size = std::to_string(width_px) + "x" + std::to_string(height_px);
  if (width_px <= 0 || height_px <= 0 || width_px > kMaxImageSidePx ||
      height_px > kMaxImageSidePx) {
    throw InputError(what + ": size " + size + " outside 1..kMaxImageSidePx = " +
                     std::to_string(kMaxImageSidePx) + " pixels");
  }
  const auto pixels = static_cast<std::size_t>(width_px) * static_cast<std::size_t>(height_px);
  if (pixels > kMaxImagePixels) {
    throw InputError(what + ": size " + size + " (" + std::to_string(pixels) +
                     " pixels) is over kMaxImagePixels = " + std::to_string(kMaxImagePixels));
  }
}

}  // namespace strata

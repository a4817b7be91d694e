#pragma once
// Image sizes accepted from outside data (PNG/JPEG files, LCM image_t messages), checked before the
// pixels are allocated or decoded, so a garbage size field cannot make a reader allocate gigabytes.
#include <cstddef>
#include <string>

namespace strata {

/// Largest image side, pixels: 4x the 4K sensors a mapper sees.
inline constexpr int kMaxImageSidePx = 16384;

/// Largest image, pixels: 64 Mpx (8192 x 8192), 256 MB as float depth.
inline constexpr std::size_t kMaxImagePixels = std::size_t{1} << 26;

/// Throws InputError "<what>: size WxH outside 1..kMaxImageSidePx = 16384 pixels" or "... is over
/// kMaxImagePixels = ..." when an image of width x height must be refused.
void checkImageSize(long long width_px, long long height_px, const std::string& what);

}  // namespace strata

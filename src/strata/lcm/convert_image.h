#pragma once
// image_t <-> DepthImage / ColorImage. Decoding checks everything a sender can get wrong (unknown
// encoding, size fields that disagree with the payload, sizes over core/image_limits.h) and throws
// InputError naming it; nothing is read past the payload.
#include <string>

#include "strata/core/image_limits.h"
#include "strata/core/types.h"
#include "strata/image_t.hpp"

namespace strata::lcm_io {

inline constexpr const char* kDepth16 = "depth16";
inline constexpr const char* kDepth32f = "depth32f";
inline constexpr const char* kRgb8 = "rgb8";
inline constexpr const char* kBgr8 = "bgr8";
inline constexpr const char* kMono8 = "mono8";

/// depth16 / depth32f -> metres (0 = no depth; NaN kept, fusion ignores it).
DepthImage decodeDepth(const image_t& image);
/// rgb8 / bgr8 / mono8 -> RGB; encoding "" -> an empty image (frame without colour).
ColorImage decodeColor(const image_t& image);

/// Metres as depth16 (round(depth_m * depth_scale), 0 where invalid or beyond 65535 units).
image_t encodeDepth16(const DepthImage& depth, float depth_scale, std::int64_t utime);
/// Metres as depth32f: exact.
image_t encodeDepth32f(const DepthImage& depth, std::int64_t utime);
/// RGB as rgb8; an empty image gives encoding "".
image_t encodeColor(const ColorImage& color, std::int64_t utime);

}  // namespace strata::lcm_io

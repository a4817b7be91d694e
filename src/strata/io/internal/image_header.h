#pragma once
// Image sizes read from PNG and JPEG headers without decoding (internal to io/image_io.cpp), so a
// header that claims a huge image is refused before OpenCV allocates its pixels.
#include <cstdint>
#include <string>
#include <vector>

namespace strata::detail {

struct ImageHeader {
  const char* format = "";  // "PNG" or "JPEG"
  long long width_px = 0;
  long long height_px = 0;
  /// Decoded bytes the header implies (PNG: scanlines with filter bytes; JPEG: 0, not bounded).
  std::uint64_t raw_bytes = 0;
};

/// Width and height from a PNG IHDR chunk or a JPEG SOFn marker. Throws InputError "<name>: ..."
/// for any other format (only PNG and JPEG are read) and for headers that are truncated or
/// corrupt.
ImageHeader readImageHeader(const std::vector<std::uint8_t>& bytes, const std::string& name);

/// checkImageSize (core/image_limits.h) on the header's size; for PNG also refuses a file too short
/// to hold the scanlines it claims even at deflate's largest ratio (kMaxDeflateRatio), which is how
/// a truncated or forged header would otherwise make the decoder allocate.
void checkImageHeader(const ImageHeader& header, std::size_t file_bytes, const std::string& name);

}  // namespace strata::detail

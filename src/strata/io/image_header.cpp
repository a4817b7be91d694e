#include "strata/io/internal/image_header.h"

#include <cstring>

#include "strata/core/error.h"
#include "strata/core/image_limits.h"

namespace strata::detail {
namespace {

constexpr std::uint8_t kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
// Deflate's largest compression ratio (zlib technical notes: a 258-byte match in 2 bits, 1032:1); a
// PNG file too small to hold its scanlines at that ratio is truncated or forged.
constexpr std::uint64_t kMaxDeflateRatio = 1032;

std::uint32_t bigEndian(const std::uint8_t* p, int bytes) {
  std::uint32_t value = 0;
  for (int i = 0; i < bytes; ++i) value = (value << 8) | p[i];
  return value;
}

int pngChannels(std::uint8_t color_type) {
  switch (color_type) {
    case 0:  // grey
    case 3:  // palette
      return 1;
    case 2:  // RGB
      return 3;
    case 4:  // grey + alpha
      return 2;
    case 6:  // RGBA
      return 4;
    default:
      return 0;
  }
}

ImageHeader readPngHeader(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  // signature (8) | IHDR length (4) = 13 | "IHDR" | width | height | bit depth | colour type | ...
  if (bytes.size() < 33 || bigEndian(&bytes[8], 4) != 13 || std::memcmp(&bytes[12], "IHDR", 4)) {
    throw InputError(name + ": PNG without a complete IHDR header (truncated or corrupt)");
  }
  ImageHeader header;
  header.format = "PNG";
  header.width_px = bigEndian(&bytes[16], 4);
  header.height_px = bigEndian(&bytes[20], 4);
  const std::uint8_t bit_depth = bytes[24];
  const int channels = pngChannels(bytes[25]);
  if (channels == 0 || bit_depth == 0 || bit_depth > 16) {
    throw InputError(name + ": PNG header has bit depth " + std::to_string(bit_depth) +
                     " and colour type " + std::to_string(bytes[25]) + " (corrupt)");
  }
  const std::uint64_t row_bits = static_cast<std::uint64_t>(header.width_px) * channels * bit_depth;
  header.raw_bytes = static_cast<std::uint64_t>(header.height_px) * (1 + (row_bits + 7) / 8);
  return header;
}

bool isJpegSof(std::uint8_t marker) {
  // SOF0..SOF15 except DHT (C4), JPG (C8) and DAC (CC), which share the range.
  return marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
}

ImageHeader readJpegHeader(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  std::size_t pos = 2;  // after SOI (FF D8)
  while (pos + 4 <= bytes.size()) {
    if (bytes[pos] != 0xFF) break;
    const std::uint8_t marker = bytes[pos + 1];
    if (marker == 0xFF) {  // fill byte
      ++pos;
      continue;
    }
    const std::size_t length = bigEndian(&bytes[pos + 2], 2);
    if (isJpegSof(marker)) {
      // length (2) | precision (1) | height (2) | width (2) | ...
      if (length < 8 || pos + 9 > bytes.size()) break;
      ImageHeader header;
      header.format = "JPEG";
      header.height_px = bigEndian(&bytes[pos + 5], 2);
      header.width_px = bigEndian(&bytes[pos + 7], 2);
      return header;
    }
    if (marker == 0xDA || length < 2) break;  // scan data before any frame header, or corrupt
    pos += 2 + length;
  }
  throw InputError(name + ": JPEG without a frame (SOF) header before its data (corrupt)");
}

}  // namespace

ImageHeader readImageHeader(const std::vector<std::uint8_t>& bytes, const std::string& name) {
  if (bytes.size() >= 8 && std::memcmp(bytes.data(), kPngSignature, 8) == 0) {
    return readPngHeader(bytes, name);
  }
  if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) {
    return readJpegHeader(bytes, name);
  }
  throw InputError(name + ": not a PNG or JPEG image (the only formats read)");
}

void checkImageHeader(const ImageHeader& header, std::size_t file_bytes, const std::string& name) {
  checkImageSize(header.width_px, header.height_px, name + ": " + header.format + " header");
  if (header.raw_bytes > kMaxDeflateRatio * file_bytes) {
    throw InputError(name + ": " + header.format + " header claims " +
                     std::to_string(header.width_px) + "x" + std::to_string(header.height_px) +
                     " pixels (" + std::to_string(header.raw_bytes) + " bytes), more than " +
                     std::to_string(file_bytes) + " bytes can hold at kMaxDeflateRatio = " +
                     std::to_string(kMaxDeflateRatio) + ":1 (truncated or corrupt)");
  }
}

}  // namespace strata::detail

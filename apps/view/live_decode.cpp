#include "view/live_decode.h"

#include <string>

#include "strata/core/error.h"
#include "strata/lcm/convert_frame.h"
#include "strata/rgbd_frame_t.hpp"

namespace strata::view {
namespace {

/// Walks an LCM payload (big-endian) far enough to check its length fields.
class WireReader {
 public:
  WireReader(const void* data, int size, const char* type)
      : data_(static_cast<const std::uint8_t*>(data)), size_(size), type_(type) {
    if (data_ == nullptr || size_ < 8)
      fail("payload of " + std::to_string(size) + " bytes is too short");
    if (size_ > lcm_io::kMaxPayloadBytes)
      fail("payload of " + std::to_string(size) + " bytes is too long");
  }
  void skip(std::int64_t bytes) {
    if (bytes < 0 || bytes > size_ - pos_) fail("truncated");
    pos_ += static_cast<int>(bytes);
  }
  std::int64_t readInt(int bytes) {
    skip(bytes);
    std::uint64_t v = 0;
    for (int i = 0; i < bytes; ++i) v = (v << 8) | data_[pos_ - bytes + i];
    if (bytes == 4) return static_cast<std::int32_t>(static_cast<std::uint32_t>(v));
    return static_cast<std::int64_t>(v);
  }
  std::uint8_t readByte() { return static_cast<std::uint8_t>(readInt(1)); }
  void expectHash(std::int64_t hash) {
    if (readInt(8) != hash) fail("type fingerprint is not " + std::string(type_) + "'s");
  }
  /// A count field of elements of at least `min_element_bytes` each; fails when they cannot follow.
  std::int32_t count(std::int64_t min_element_bytes, const char* what) {
    const auto n = static_cast<std::int32_t>(readInt(4));
    if (n < 0 || n * min_element_bytes > size_ - pos_) {
      fail(std::string(what) + " claims " + std::to_string(n) + " elements, " +
           std::to_string(size_ - pos_) + " bytes left");
    }
    return n;
  }
  /// NOTE: an LCM string's length counts its NUL, so it is at least 1 (lcm-gen computes length -
  /// 1).
  void skipString() {
    const auto length = static_cast<std::int32_t>(readInt(4));
    if (length < 1) fail("string length " + std::to_string(length));
    skip(length);
  }
  int pos() const { return pos_; }
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(std::string(type_) + ": " + why + " at byte " + std::to_string(pos_) + " of " +
                     std::to_string(size_));
  }

 private:
  const std::uint8_t* data_;
  int size_;
  const char* type_;
  int pos_ = 0;
};

/// Decodes after the walk: lcm-gen's decoder must use every byte the walk accepted.
template <typename Message>
Message decodeChecked(const void* data, int size, const char* type) {
  Message message;
  int used = -1;
  try {
    used = message.decode(data, 0, size);
  } catch (const std::exception& e) {
    throw InputError(std::string(type) + ": undecodable payload (" + e.what() + ")");
  }
  if (used != size) throw InputError(std::string(type) + ": payload does not decode to its size");
  return message;
}

void skipMesh(WireReader& in) {
  in.skip(in.count(12, "vertices") * std::int64_t{12});
  in.skip(in.count(12, "triangles") * std::int64_t{12});
}

}  // namespace

mesh_update_t decodeMeshUpdate(const void* data, int size) {
  WireReader in(data, size, "mesh_update_t");
  in.expectHash(mesh_update_t::getHash());
  in.skip(8 + 8 + 8 + 1 + 4);  // utime, last_frame_utime, sequence, full, voxel_size_m
  const std::int32_t blocks = in.count(20, "blocks");
  for (std::int32_t b = 0; b < blocks; ++b) {
    in.skip(12);  // index
    const std::int32_t vertices = in.count(15, "block vertices");
    in.skip(vertices * std::int64_t{15});  // positions and colours
    in.skip(in.count(12, "block triangles") * std::int64_t{12});
  }
  return decodeChecked<mesh_update_t>(data, size, "mesh_update_t");
}

esdf_slice_t decodeEsdfSlice(const void* data, int size) {
  WireReader in(data, size, "esdf_slice_t");
  in.expectHash(esdf_slice_t::getHash());
  in.skip(8 + 8 + 16);  // utime, last_frame_utime, z, resolution, origin
  const auto width = static_cast<std::int32_t>(in.readInt(4));
  const auto height = static_cast<std::int32_t>(in.readInt(4));
  if (width < 0 || height < 0) in.fail("negative grid size");
  in.skip(std::int64_t{width} * height * 5);  // distances and states
  return decodeChecked<esdf_slice_t>(data, size, "esdf_slice_t");
}

map_stats_t decodeMapStats(const void* data, int size) {
  WireReader in(data, size, "map_stats_t");
  in.expectHash(map_stats_t::getHash());
  in.skip(8 + 6 * 8 + 2 * 4 + 8 + 8 + 2 * 4 + 8 + 4 + 1 + 8);  // utime .. last_command_id
  in.skipString();                                             // last_command_result
  const std::int32_t channels = in.count(13, "channels");
  for (std::int32_t c = 0; c < channels; ++c) in.skipString();
  in.skip(channels * std::int64_t{8});
  return decodeChecked<map_stats_t>(data, size, "map_stats_t");
}

change_event_t decodeChangeEvent(const void* data, int size) {
  WireReader in(data, size, "change_event_t");
  in.expectHash(change_event_t::getHash());
  in.skip(8 + 3 * 4 + 3 * 12);  // utime, session, object_id, num_objects, centroid, box
  skipMesh(in);
  return decodeChecked<change_event_t>(data, size, "change_event_t");
}

object_update_t decodeObjectUpdate(const void* data, int size) {
  WireReader in(data, size, "object_update_t");
  in.expectHash(object_update_t::getHash());
  in.skip(8 + 4 * 4 + 1 + 4 + 4);  // utime, session .. model_id, new_model, merged, area
  in.skip(in.count(140, "instances") * std::int64_t{140});
  skipMesh(in);
  return decodeChecked<object_update_t>(data, size, "object_update_t");
}

std::optional<pose_t> framePose(const void* data, int size) {
  WireReader in(data, size, "rgbd_frame_t");
  in.expectHash(rgbd_frame_t::getHash());
  in.skip(8);       // utime
  in.skipString();  // camera_id
  in.skip(8);       // sequence
  for (int image = 0; image < 2; ++image) {
    in.skip(8);       // utime
    in.skipString();  // encoding
    in.skip(12);      // width, height, depth_scale
    in.skip(in.count(1, "image data"));
  }
  if (in.readByte() == 0) return std::nullopt;
  const int start = in.pos();
  in.skip(8);
  in.skipString();  // parent_frame
  in.skipString();  // child_frame
  in.skip(3 * 8 + 4 * 8 + 36 * 8);
  if (in.pos() != size) in.fail("bytes left over after the pose");
  pose_t pose;
  if (pose._decodeNoHash(data, start, size - start) != size - start)
    in.fail("pose does not decode");
  return pose;
}

}  // namespace strata::view

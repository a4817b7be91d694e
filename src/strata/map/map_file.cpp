#include "strata/map/map_file.h"

#include <cstring>
#include <sstream>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/file_limits.h"

namespace strata {
namespace {

constexpr char kMagic[8] = {'S', 'T', 'R', 'A', 'T', 'A', 'M', 'P'};
// Checked before the file is read into memory: 8 GiB holds ~1.4 million 6 KiB blocks, far beyond
// any map a session builds, and still fits the memory of the machines that would load it.
constexpr FileSizeLimit kMaxMapFileBytes{"kMaxMapFileBytes", std::uint64_t{8} << 30};

class ByteWriter {
 public:
  template <typename T>
  void put(const T& value) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    bytes_.insert(bytes_.end(), p, p + sizeof(T));
  }
  void putBytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const std::uint8_t*>(data);
    bytes_.insert(bytes_.end(), p, p + size);
  }
  std::vector<std::uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<std::uint8_t> bytes_;
};

class ByteReader {
 public:
  ByteReader(const std::vector<std::uint8_t>& bytes, std::size_t end, const std::string& what)
      : bytes_(bytes), end_(end), what_(what) {}
  template <typename T>
  T get(const char* field) {
    T value;
    getBytes(&value, sizeof(T), field);
    return value;
  }
  void getBytes(void* out, std::size_t size, const char* field) {
    if (end_ - offset_ < size) {
      std::ostringstream msg;
      msg << "map file '" << what_ << "' is truncated: " << field << " needs " << size
          << " bytes at offset " << offset_ << " but only " << end_ - offset_ << " remain";
      throw InputError(msg.str());
    }
    std::memcpy(out, bytes_.data() + offset_, size);
    offset_ += size;
  }
  std::size_t remaining() const { return end_ - offset_; }

 private:
  const std::vector<std::uint8_t>& bytes_;
  std::size_t end_;
  std::size_t offset_ = 0;
  std::string what_;
};

void putConfig(ByteWriter& w, const MapConfig& c) {
  w.put(c.voxel_size_m);
  w.put(c.truncation_voxels);
  w.put(c.max_weight);
  w.put(c.min_depth_m);
  w.put(c.max_depth_m);
  w.put(static_cast<std::uint32_t>(c.weight_mode));
  w.put(static_cast<std::uint32_t>(c.weight_dropoff ? 1 : 0));
  w.put(c.dropoff_start_voxels);
  w.put(c.initial_block_capacity);
  w.put(c.initial_hash_capacity);
  w.put(static_cast<std::uint32_t>(c.distance_mode));
  w.put(c.normal_max_relative_jump);
  w.put(c.max_block_capacity);
  w.put(static_cast<std::uint32_t>(c.allocate_free_space ? 1 : 0));
  w.put(c.free_space_pixel_stride);
}
constexpr std::uint32_t kConfigBytes = 60;

MapConfig getConfig(ByteReader& r) {
  MapConfig c;
  c.voxel_size_m = r.get<float>("voxel_size_m");
  c.truncation_voxels = r.get<float>("truncation_voxels");
  c.max_weight = r.get<float>("max_weight");
  c.min_depth_m = r.get<float>("min_depth_m");
  c.max_depth_m = r.get<float>("max_depth_m");
  c.weight_mode = static_cast<WeightMode>(r.get<std::uint32_t>("weight_mode"));
  c.weight_dropoff = r.get<std::uint32_t>("weight_dropoff") != 0;
  c.dropoff_start_voxels = r.get<float>("dropoff_start_voxels");
  c.initial_block_capacity = r.get<std::uint32_t>("initial_block_capacity");
  c.initial_hash_capacity = r.get<std::uint32_t>("initial_hash_capacity");
  c.distance_mode = static_cast<DistanceMode>(r.get<std::uint32_t>("distance_mode"));
  c.normal_max_relative_jump = r.get<float>("normal_max_relative_jump");
  c.max_block_capacity = r.get<std::uint32_t>("max_block_capacity");
  c.allocate_free_space = r.get<std::uint32_t>("allocate_free_space") != 0;
  c.free_space_pixel_stride = r.get<std::uint32_t>("free_space_pixel_stride");
  return c;
}

constexpr std::uint32_t kRecordBytes = 24;

void putRecord(ByteWriter& w, const MapSessionRecord& r) {
  w.put(kRecordBytes);
  w.put(r.sessions_ended);
  w.put(static_cast<std::uint32_t>(r.session_open ? 1 : 0));
  w.put(r.session_frames);
  w.put(r.frames);
}

MapSessionRecord getRecord(ByteReader& r, const std::string& prefix) {
  if (r.get<std::uint32_t>("session record size") != kRecordBytes) {
    throw InputError(prefix + " has an unexpected session record size");
  }
  MapSessionRecord record;
  record.sessions_ended = r.get<std::uint32_t>("sessions ended");
  const auto open = r.get<std::uint32_t>("session open");
  if (open > 1) throw InputError(prefix + " has an invalid session-open flag");
  record.session_open = open == 1;
  record.session_frames = r.get<std::uint64_t>("session frames");
  record.frames = r.get<std::uint64_t>("frames");
  if (record.session_frames > record.frames || (!record.session_open && record.session_frames)) {
    throw InputError(prefix + " has an inconsistent session record (" +
                     std::to_string(record.session_frames) + " frames in the open session of " +
                     std::to_string(record.frames) + ")");
  }
  return record;
}

void putLayer(ByteWriter& w, std::uint32_t id, const TsdfMap& map) {
  w.put(id);
  w.put(static_cast<std::uint32_t>(sizeof(TsdfVoxel)));
  const std::vector<BlockIndex> indices = map.sortedBlockIndices();
  w.put(static_cast<std::uint64_t>(indices.size()));
  for (const BlockIndex& b : indices) {
    w.put(b.x());
    w.put(b.y());
    w.put(b.z());
    w.putBytes(map.findBlock(b)->data(), sizeof(TsdfBlock));
  }
}

void getLayer(ByteReader& r, TsdfMap& map, const std::string& prefix) {
  const auto block_count = r.get<std::uint64_t>("block count");
  if (block_count > r.remaining() / (12 + sizeof(TsdfBlock))) {
    throw InputError(prefix + " is truncated: it declares " + std::to_string(block_count) +
                     " blocks but holds fewer");
  }
  for (std::uint64_t i = 0; i < block_count; ++i) {
    BlockIndex b;
    b.x() = r.get<std::int32_t>("block x");
    b.y() = r.get<std::int32_t>("block y");
    b.z() = r.get<std::int32_t>("block z");
    if (!blockIndexInRange(b) || map.findBlock(b) != nullptr) {
      throw InputError(prefix + " has an invalid or repeated block index");
    }
    r.getBytes(map.allocateBlock(b).data(), sizeof(TsdfBlock), "voxels");
  }
}

bool sameConfig(const MapConfig& a, const MapConfig& b) {
  ByteWriter wa, wb;
  putConfig(wa, a);
  putConfig(wb, b);
  return wa.bytes() == wb.bytes();
}

/// The bytes of a file holding `map`, and `static_map` and `record` where given (no copies of
/// the maps: they can be most of the memory).
std::vector<std::uint8_t> serialize(const TsdfMap& map, const TsdfMap* static_map,
                                    const MapSessionRecord* record) {
  const bool open = record && record->session_open;
  if ((static_map != nullptr) != open) {
    throw InputError(open ? "map file: an open session needs the static layer"
                          : "map file: a static layer needs an open session in the record");
  }
  if (static_map && !sameConfig(static_map->config(), map.config())) {
    throw InputError("map file: the static layer's config differs from the map's");
  }
  ByteWriter w;
  w.putBytes(kMagic, sizeof(kMagic));
  w.put(record ? kMapStateFormatVersion : kMapFormatVersion);
  w.put(kConfigBytes);
  putConfig(w, map.config());
  if (record) putRecord(w, *record);
  w.put(std::uint32_t{static_map ? 2u : 1u});  // layer count
  putLayer(w, kLayerTsdf, map);
  if (static_map) putLayer(w, kLayerStaticTsdf, *static_map);
  const std::uint32_t crc = crc32(w.bytes().data(), w.bytes().size());
  w.put(crc);
  return std::move(w.bytes());
}

}  // namespace

std::vector<std::uint8_t> serializeMapFile(const MapFileContents& contents) {
  return serialize(contents.map, contents.static_map ? &*contents.static_map : nullptr,
                   contents.sessions ? &*contents.sessions : nullptr);
}

std::vector<std::uint8_t> serializeMap(const TsdfMap& map) {
  return serialize(map, nullptr, nullptr);
}

MapFileContents deserializeMapFile(const std::vector<std::uint8_t>& bytes,
                                   const std::string& what) {
  const std::string prefix = "map file '" + what + "'";
  if (bytes.size() < sizeof(kMagic) || std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    throw InputError(prefix + " is not a Strata map (bad magic bytes)");
  }
  if (bytes.size() < sizeof(kMagic) + 8 + 4) throw InputError(prefix + " is truncated (no header)");
  const std::size_t body = bytes.size() - 4;
  ByteReader r(bytes, body, what);
  char magic[8];
  r.getBytes(magic, sizeof(magic), "magic");
  const auto version = r.get<std::uint32_t>("format version");
  if (version != kMapFormatVersion && version != kMapStateFormatVersion) {
    throw InputError(prefix + " has format version " + std::to_string(version) +
                     "; this build reads versions " + std::to_string(kMapFormatVersion) + " and " +
                     std::to_string(kMapStateFormatVersion));
  }
  std::uint32_t stored_crc = 0;
  std::memcpy(&stored_crc, bytes.data() + body, 4);
  if (crc32(bytes.data(), body) != stored_crc) {
    throw InputError(prefix + " is corrupted or truncated (checksum mismatch)");
  }
  if (r.get<std::uint32_t>("config size") != kConfigBytes) {
    throw InputError(prefix + " has an unexpected config size");
  }
  const MapConfig config = getConfig(r);
  try {
    config.validate();
  } catch (const InputError& e) {
    throw InputError(prefix + ": " + e.what());
  }
  MapFileContents contents{TsdfMap(config), std::nullopt, std::nullopt};
  if (version == kMapStateFormatVersion) contents.sessions = getRecord(r, prefix);
  const bool open = contents.sessions && contents.sessions->session_open;
  const auto layers = r.get<std::uint32_t>("layer count");
  if (layers != (open ? 2u : 1u)) {
    throw InputError(prefix + " holds " + std::to_string(layers) + " layers; " +
                     (open ? "a mapper state with an open session holds 2"
                           : "a map without an open session holds 1"));
  }
  for (std::uint32_t l = 0; l < layers; ++l) {
    const auto layer_id = r.get<std::uint32_t>("layer id");
    const auto voxel_bytes = r.get<std::uint32_t>("bytes per voxel");
    const std::uint32_t expected = l == 0 ? kLayerTsdf : kLayerStaticTsdf;
    if (layer_id != expected || voxel_bytes != sizeof(TsdfVoxel)) {
      throw InputError(prefix + " has an unknown layer (id " + std::to_string(layer_id) +
                       " where layer " + std::to_string(expected) + " belongs)");
    }
    if (l == 0) {
      getLayer(r, contents.map, prefix);
    } else {
      contents.static_map.emplace(config);
      getLayer(r, *contents.static_map, prefix);
    }
  }
  if (r.remaining() != 0) throw InputError(prefix + " has trailing bytes after the last layer");
  return contents;
}

TsdfMap deserializeMap(const std::vector<std::uint8_t>& bytes, const std::string& what) {
  return std::move(deserializeMapFile(bytes, what).map);
}

void saveMap(const TsdfMap& map, const std::string& path) {
  writeFileAtomically(path, serializeMap(map));
}

TsdfMap loadMap(const std::string& path) {
  return deserializeMap(readFileBounded(path, kMaxMapFileBytes, "map file"), path);
}

void saveMapFile(const MapFileContents& contents, const std::string& path) {
  writeFileAtomically(path, serializeMapFile(contents));
}

MapFileContents loadMapFile(const std::string& path) {
  return deserializeMapFile(readFileBounded(path, kMaxMapFileBytes, "map file"), path);
}

}  // namespace strata

#include "strata/objects/object_database_file.h"

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <set>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/map/map_file.h"
#include "strata/store/session_store.h"

namespace strata::objects {

namespace {

constexpr char kMagic[9] = {'S', 'T', 'R', 'A', 'T', 'A', 'O', 'B', 'J'};
constexpr std::size_t kHeaderBytes = sizeof(kMagic) + 4 + 4 + 8;
/// Smallest encoded instance and model: counts read from a file are checked against the bytes
/// left before anything is allocated.
constexpr std::size_t kInstanceBytes = 4 + 4 + 12 * 8 + 8 + 4 + 1;
constexpr std::size_t kModelBytes = 4 + 4 + 4 + 4;
/// An instance's flags byte.
constexpr unsigned kMergedBit = 1;    // versions 1 and 2
constexpr unsigned kPoseOpenBit = 2;  // version 2: pose_constrained is false

/// FNV-1a, 64 bit (Fowler, Noll, Vo).
std::uint64_t fnv1a64(const std::uint8_t* data, std::size_t size) {
  std::uint64_t hash = 14695981039346656037ull;
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= data[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

class Writer {
 public:
  template <typename T>
  void put(const T& value) {
    const auto* p = reinterpret_cast<const std::uint8_t*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  void putBytes(const std::vector<std::uint8_t>& more) {
    bytes.insert(bytes.end(), more.begin(), more.end());
  }
  std::vector<std::uint8_t> bytes;
};

/// Bounds-checked reads of the payload; errors name the source and the field.
class Reader {
 public:
  Reader(const std::uint8_t* data, std::size_t size, const std::string& name)
      : data_(data), size_(size), name_(name) {}
  template <typename T>
  T get(const char* field) {
    T value;
    std::memcpy(&value, take(sizeof(T), field), sizeof(T));
    return value;
  }
  std::vector<std::uint8_t> getBytes(std::size_t count, const char* field) {
    const std::uint8_t* p = take(count, field);
    return std::vector<std::uint8_t>(p, p + count);
  }
  /// A count of records of at least `record_bytes` each that the remaining bytes can hold.
  std::uint32_t getCount(std::size_t record_bytes, const char* field) {
    const auto count = get<std::uint32_t>(field);
    if (static_cast<std::uint64_t>(count) * record_bytes > size_ - offset_) {
      fail(std::string(field) + " " + std::to_string(count) + " cannot fit in the " +
           std::to_string(size_ - offset_) + " bytes left");
    }
    return count;
  }
  std::size_t remaining() const { return size_ - offset_; }
  [[noreturn]] void fail(const std::string& what) const {
    throw InputError("object database '" + name_ + "' is corrupt: " + what);
  }

 private:
  const std::uint8_t* take(std::size_t count, const char* field) {
    if (size_ - offset_ < count) {
      fail(std::string("the payload ends inside ") + field + " at byte " + std::to_string(offset_));
    }
    const std::uint8_t* p = data_ + offset_;
    offset_ += count;
    return p;
  }
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
  std::string name_;
};

void putInstance(Writer& w, const ObjectInstance& instance) {
  w.put(static_cast<std::int32_t>(instance.session));
  w.put(static_cast<std::int32_t>(instance.segment_id));
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) w.put(instance.T_W_M.matrix()(row, col));
  }
  w.put(instance.match_score);
  w.put(instance.observed_area_m2);
  w.put(static_cast<std::uint8_t>((instance.merged ? kMergedBit : 0) |
                                  (instance.pose_constrained ? 0 : kPoseOpenBit)));
}

ObjectInstance getInstance(Reader& r, std::uint32_t version) {
  ObjectInstance instance;
  instance.session = r.get<std::int32_t>("instance session");
  instance.segment_id = r.get<std::int32_t>("instance segment");
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 4; ++col) instance.T_W_M.matrix()(row, col) = r.get<double>("pose");
  }
  const Eigen::Matrix3d R = instance.T_W_M.linear();
  if (!instance.T_W_M.matrix().allFinite() ||
      !(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-6)) {
    r.fail("an instance pose of session " + std::to_string(instance.session) +
           " is not a rigid transform");
  }
  instance.match_score = r.get<double>("match score");
  instance.observed_area_m2 = r.get<float>("observed area");
  // Version 1 wrote 0 or 1 (merged); version 2 added the open-pose bit.
  const auto flags = r.get<std::uint8_t>("instance flags");
  const unsigned known = version >= 2 ? (kMergedBit | kPoseOpenBit) : kMergedBit;
  if ((flags & ~known) != 0) {
    r.fail("an instance of session " + std::to_string(instance.session) + " has unknown flags " +
           std::to_string(flags));
  }
  instance.merged = (flags & kMergedBit) != 0;
  instance.pose_constrained = (flags & kPoseOpenBit) == 0;
  return instance;
}

void putModel(Writer& w, const ObjectModel& model) {
  w.put(static_cast<std::int32_t>(model.id));
  w.put(static_cast<std::int32_t>(model.merged_observations));
  w.put(static_cast<std::uint32_t>(model.instances.size()));
  for (const ObjectInstance& instance : model.instances) putInstance(w, instance);
  const std::vector<std::uint8_t> tsdf = serializeMap(model.tsdf);
  w.put(static_cast<std::uint32_t>(tsdf.size()));
  w.putBytes(tsdf);
}

ObjectModel getModel(Reader& r, std::uint32_t version, const std::string& name) {
  ObjectModel model;
  model.id = r.get<std::int32_t>("model id");
  model.merged_observations = r.get<std::int32_t>("merged observations");
  const std::uint32_t instances = r.getCount(kInstanceBytes, "instance count");
  for (std::uint32_t i = 0; i < instances; ++i) model.instances.push_back(getInstance(r, version));
  const auto tsdf_bytes = r.get<std::uint32_t>("TSDF size");
  model.tsdf =
      deserializeMap(r.getBytes(tsdf_bytes, "TSDF"), name + " model " + std::to_string(model.id));
  return model;
}

std::string headerError(const std::string& name, const std::string& what) {
  return "object database '" + name + "' " + what;
}

/// The payload after checking the header: magic, version (returned in `version`), length,
/// checksum.
Reader checkedPayload(const std::string& bytes, const std::string& name, std::uint32_t& version) {
  if (bytes.size() < kHeaderBytes) {
    throw InputError(headerError(name, "is truncated: " + std::to_string(bytes.size()) +
                                           " bytes, shorter than its " +
                                           std::to_string(kHeaderBytes) + "-byte header"));
  }
  if (std::memcmp(bytes.data(), kMagic, sizeof(kMagic)) != 0) {
    throw InputError(headerError(name, "is not a Strata object database (no STRATAOBJ magic)"));
  }
  const auto* data = reinterpret_cast<const std::uint8_t*>(bytes.data());
  Reader header(data + sizeof(kMagic), kHeaderBytes - sizeof(kMagic), name);
  version = header.get<std::uint32_t>("version");
  const auto payload_bytes = header.get<std::uint32_t>("payload size");
  const auto checksum = header.get<std::uint64_t>("checksum");
  if (version == 0 || version > kObjectDatabaseFormatVersion) {
    throw InputError(headerError(name, "was written by format version " + std::to_string(version) +
                                           "; this build reads up to " +
                                           std::to_string(kObjectDatabaseFormatVersion)));
  }
  const std::size_t present = bytes.size() - kHeaderBytes;
  if (present < payload_bytes) {
    throw InputError(headerError(name, "is truncated: its header announces " +
                                           std::to_string(payload_bytes) + " payload bytes, " +
                                           std::to_string(present) + " are present"));
  }
  if (present > payload_bytes) {
    throw InputError(headerError(name, "is corrupt: " + std::to_string(present - payload_bytes) +
                                           " bytes follow its payload"));
  }
  const std::uint64_t actual = fnv1a64(data + kHeaderBytes, payload_bytes);
  if (actual != checksum) {
    throw InputError(headerError(name, "is corrupt: checksum mismatch (payload " +
                                           std::to_string(actual) + ", header " +
                                           std::to_string(checksum) + ")"));
  }
  return Reader(data + kHeaderBytes, payload_bytes, name);
}

}  // namespace

std::string serializeObjectDatabase(const ObjectDatabase& database) {
  Writer payload;
  const DatabaseConfig& config = database.config();
  payload.put(config.registration.voxel_size_m);
  payload.put(config.model.voxel_size_m);
  const std::vector<int> sessions = database.sessions();
  payload.put(static_cast<std::uint32_t>(sessions.size()));
  for (const int s : sessions) payload.put(static_cast<std::int32_t>(s));
  payload.put(static_cast<std::uint32_t>(database.models().size()));
  for (const ObjectModel& model : database.models()) putModel(payload, model);
  if (payload.bytes.size() > std::numeric_limits<std::uint32_t>::max()) {
    throw Error("object database of " + std::to_string(payload.bytes.size()) +
                " bytes exceeds the 4 GiB that the format holds");
  }
  Writer file;
  file.bytes.assign(kMagic, kMagic + sizeof(kMagic));
  file.put(static_cast<std::uint32_t>(kObjectDatabaseFormatVersion));
  file.put(static_cast<std::uint32_t>(payload.bytes.size()));
  file.put(fnv1a64(payload.bytes.data(), payload.bytes.size()));
  file.putBytes(payload.bytes);
  return std::string(file.bytes.begin(), file.bytes.end());
}

ObjectDatabase deserializeObjectDatabase(const std::string& bytes, const std::string& name,
                                         const DatabaseConfig& config) {
  std::uint32_t version = 0;
  Reader r = checkedPayload(bytes, name, version);
  DatabaseConfig loaded = config;
  loaded.registration.voxel_size_m = r.get<float>("map voxel size");
  loaded.model.voxel_size_m = r.get<float>("model voxel size");
  // A voxel edge outside [0.1 mm, 10 m] (or not finite) is corruption, not a map: sample cells
  // of such a size overflow integer coordinates.
  const auto plausible = [](float v) { return std::isfinite(v) && v >= 1e-4f && v <= 10.0f; };
  if (!plausible(loaded.registration.voxel_size_m) ||
      !(loaded.model.voxel_size_m == 0.0f || plausible(loaded.model.voxel_size_m))) {
    r.fail("voxel sizes " + std::to_string(loaded.registration.voxel_size_m) + " / " +
           std::to_string(loaded.model.voxel_size_m) + " m");
  }
  std::vector<int> sessions(r.getCount(4, "session count"));
  for (int& s : sessions) s = r.get<std::int32_t>("session");
  std::vector<ObjectModel> models(r.getCount(kModelBytes, "model count"));
  std::set<int> ids;
  const float spacing_m =
      loaded.observation.sample_spacing_voxels * loaded.registration.voxel_size_m;
  for (ObjectModel& model : models) {
    model = getModel(r, version, name);
    if (model.id <= 0 || !ids.insert(model.id).second) {
      r.fail("model id " + std::to_string(model.id) + " is not positive or repeats");
    }
    refreshModel(model, spacing_m, loaded.model);  // meshes and samples are derived
  }
  if (r.remaining() != 0) r.fail(std::to_string(r.remaining()) + " bytes after the last model");
  return ObjectDatabase::fromParts(loaded, std::move(models), std::move(sessions));
}

void saveObjectDatabase(const ObjectDatabase& database, const std::string& path) {
  const std::string bytes = serializeObjectDatabase(database);
  writeFileAtomically(path, std::vector<std::uint8_t>(bytes.begin(), bytes.end()));
}

ObjectDatabase loadObjectDatabase(const std::string& path, const DatabaseConfig& config) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw InputError("object database '" + path + "' does not exist (or is not a file)");
  }
  const std::vector<std::uint8_t> bytes = readFile(path);
  return deserializeObjectDatabase(std::string(bytes.begin(), bytes.end()), path, config);
}

void saveObjectDatabase(const ObjectDatabase& database, store::Store& store) {
  const std::string bytes = serializeObjectDatabase(database);
  store.setObjectDatabase(
      {kObjectDatabaseFormatVersion, std::vector<std::uint8_t>(bytes.begin(), bytes.end())});
}

bool loadObjectDatabase(store::Store& store, ObjectDatabase& database,
                        const DatabaseConfig& config) {
  const std::optional<store::ObjectDatabaseBlob> blob = store.objectDatabase();
  if (!blob) return false;
  const std::string name = store.path() + "' table 'object_database";
  if (blob->format_version > kObjectDatabaseFormatVersion) {
    throw InputError("object database '" + name + "' was written by format version " +
                     std::to_string(blob->format_version) + "; this build reads up to " +
                     std::to_string(kObjectDatabaseFormatVersion));
  }
  database =
      deserializeObjectDatabase(std::string(blob->bytes.begin(), blob->bytes.end()), name, config);
  return true;
}

}  // namespace strata::objects

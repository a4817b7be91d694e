// The object database file and its copy in the session store: round trips that keep models,
// instances and TSDF voxels; corrupt, truncated, newer and missing files refused naming the file;
// a failed save leaving the previous file as it was.
#include <gtest/gtest.h>

#include <cerrno>
#include <filesystem>
#include <functional>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/file_faults.h"
#include "object_test_scene.h"
#include "strata/objects/object_database_file.h"
#include "strata/store/session_store.h"
#include "test_utils.h"

namespace strata::objects {
namespace {

namespace fs = std::filesystem;

void expectSameTsdf(const TsdfMap& a, const TsdfMap& b) {
  EXPECT_EQ(a.config().voxel_size_m, b.config().voxel_size_m);
  ASSERT_EQ(a.sortedBlockIndices(), b.sortedBlockIndices());
  for (const BlockIndex& index : a.sortedBlockIndices()) {
    const TsdfBlock& x = *a.findBlock(index);
    const TsdfBlock& y = *b.findBlock(index);
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      ASSERT_EQ(x[i].tsdf_m, y[i].tsdf_m);
      ASSERT_EQ(x[i].weight, y[i].weight);
      ASSERT_EQ(x[i].color_rgba, y[i].color_rgba);
    }
  }
}

void expectSameDatabase(const ObjectDatabase& a, const ObjectDatabase& b) {
  EXPECT_EQ(a.sessions(), b.sessions());
  EXPECT_EQ(a.config().registration.voxel_size_m, b.config().registration.voxel_size_m);
  ASSERT_EQ(a.models().size(), b.models().size());
  for (std::size_t m = 0; m < a.models().size(); ++m) {
    const ObjectModel& x = a.models()[m];
    const ObjectModel& y = b.models()[m];
    EXPECT_EQ(x.id, y.id);
    EXPECT_EQ(x.merged_observations, y.merged_observations);
    ASSERT_EQ(x.instances.size(), y.instances.size());
    for (std::size_t i = 0; i < x.instances.size(); ++i) {
      EXPECT_EQ(x.instances[i].session, y.instances[i].session);
      EXPECT_EQ(x.instances[i].segment_id, y.instances[i].segment_id);
      EXPECT_TRUE(x.instances[i].T_W_M.matrix() == y.instances[i].T_W_M.matrix());
      EXPECT_EQ(x.instances[i].match_score, y.instances[i].match_score);
      EXPECT_EQ(x.instances[i].observed_area_m2, y.instances[i].observed_area_m2);
      EXPECT_EQ(x.instances[i].merged, y.instances[i].merged);
      EXPECT_EQ(x.instances[i].pose_constrained, y.instances[i].pose_constrained);
    }
    expectSameTsdf(x.tsdf, y.tsdf);
    // Derived parts are rebuilt on load from the same voxels.
    EXPECT_EQ(x.mesh_M.triangles.size(), y.mesh_M.triangles.size());
    EXPECT_EQ(x.surface_M.size(), y.surface_M.size());
    EXPECT_FLOAT_EQ(x.surface_area_m2, y.surface_area_m2);
  }
}

std::string inputErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

void writeBytes(const fs::path& path, std::vector<std::uint8_t> bytes) {
  writeFileAtomically(path.string(), bytes);
}

TEST(ObjectDatabaseFile, RoundTripKeepsModelsInstancesAndVoxels) {
  const ObjectDatabase& database = test::threeSessions().database;
  ASSERT_FALSE(database.models().empty());
  const fs::path dir = test::freshTempDir("objects_file_round_trip");
  const fs::path path = dir / "db.objects";
  saveObjectDatabase(database, path.string());
  const ObjectDatabase loaded = loadObjectDatabase(path.string());
  expectSameDatabase(database, loaded);
  // Deterministic: the loaded database writes the same bytes.
  EXPECT_EQ(serializeObjectDatabase(loaded), serializeObjectDatabase(database));
  fs::remove_all(dir);
}

// Version 2 added the open-pose flag of an instance; a version 1 file (flags 0 or 1) reads with
// every pose constrained, and a version 1 file with the new flag is corrupt.
TEST(ObjectDatabaseFile, OpenPoseFlagRoundTripsAndVersionOneFilesAreRead) {
  const ObjectDatabase& database = test::threeSessions().database;
  ASSERT_FALSE(database.models().empty());
  std::vector<ObjectModel> models = database.models();
  ASSERT_FALSE(models.front().instances.empty());
  models.front().instances.front().pose_constrained = false;
  models.front().instances.front().merged = false;
  const ObjectDatabase open =
      ObjectDatabase::fromParts(database.config(), models, database.sessions());
  const std::string open_bytes = serializeObjectDatabase(open);
  const ObjectDatabase loaded = deserializeObjectDatabase(open_bytes, "open");
  EXPECT_FALSE(loaded.models().front().instances.front().pose_constrained);
  expectSameDatabase(open, loaded);

  auto asVersion1 = [](std::string bytes) {
    bytes[9] = 1;  // u32 version after the 9-byte magic; the checksum covers the payload only
    return bytes;
  };
  const ObjectDatabase v1 =
      deserializeObjectDatabase(asVersion1(serializeObjectDatabase(database)), "v1");
  expectSameDatabase(database, v1);
  for (const ObjectModel& m : v1.models()) {
    for (const ObjectInstance& i : m.instances) EXPECT_TRUE(i.pose_constrained);
  }
  const std::string message =
      inputErrorOf([&] { deserializeObjectDatabase(asVersion1(open_bytes), "v1-open"); });
  EXPECT_NE(message.find("unknown flags"), std::string::npos) << message;
}

TEST(ObjectDatabaseFile, BadFilesAreRefusedNamingTheFile) {
  const ObjectDatabase& database = test::threeSessions().database;
  const fs::path dir = test::freshTempDir("objects_file_bad");
  const fs::path good = dir / "good.objects";
  saveObjectDatabase(database, good.string());
  const std::vector<std::uint8_t> bytes = readFile(good.string());
  const auto load = [](const fs::path& p) { return [p] { loadObjectDatabase(p.string()); }; };

  const fs::path corrupt = dir / "corrupt.objects";
  std::vector<std::uint8_t> flipped = bytes;
  flipped[flipped.size() / 2] ^= 0x40;
  writeBytes(corrupt, flipped);
  std::string message = inputErrorOf(load(corrupt));
  EXPECT_NE(message.find(corrupt.string()), std::string::npos) << message;
  EXPECT_NE(message.find("checksum mismatch"), std::string::npos) << message;

  const fs::path truncated = dir / "truncated.objects";
  writeBytes(truncated, std::vector<std::uint8_t>(bytes.begin(), bytes.end() - 100));
  message = inputErrorOf(load(truncated));
  EXPECT_NE(message.find(truncated.string()), std::string::npos) << message;
  EXPECT_NE(message.find("truncated"), std::string::npos) << message;
  writeBytes(truncated, std::vector<std::uint8_t>(bytes.begin(), bytes.begin() + 10));
  EXPECT_NE(inputErrorOf(load(truncated)).find("header"), std::string::npos);

  const fs::path newer = dir / "newer.objects";
  std::vector<std::uint8_t> version3 = bytes;
  version3[9] = 3;  // u32 version after the 9-byte magic, little endian
  writeBytes(newer, version3);
  message = inputErrorOf(load(newer));
  EXPECT_NE(message.find(newer.string()), std::string::npos) << message;
  EXPECT_NE(message.find("written by format version 3; this build reads up to 2"),
            std::string::npos)
      << message;

  const fs::path foreign = dir / "foreign.objects";
  writeBytes(foreign, std::vector<std::uint8_t>(100, 'x'));
  EXPECT_NE(inputErrorOf(load(foreign)).find("magic"), std::string::npos);

  const fs::path missing = dir / "missing.objects";
  message = inputErrorOf(load(missing));
  EXPECT_NE(message.find(missing.string()), std::string::npos) << message;
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  fs::remove_all(dir);
}

TEST(ObjectDatabaseFile, FailedSaveLeavesThePreviousFileIntact) {
  const fs::path dir = test::freshTempDir("objects_file_failed_save");
  const fs::path path = dir / "db.objects";
  saveObjectDatabase(ObjectDatabase{}, path.string());
  const std::vector<std::uint8_t> before = readFile(path.string());
  {
    // As an unwritable folder fails (tests may run as root, where permissions do not stop a
    // write): the temporary file cannot be created.
    const ScopedFileFault fault(FileStep::kOpen, EACCES);
    try {
      saveObjectDatabase(test::threeSessions().database, path.string());
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
  }
  EXPECT_EQ(readFile(path.string()), before);
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}), 1);
  fs::remove_all(dir);
}

TEST(ObjectDatabaseFile, StoreCopyRoundTrips) {
  const ObjectDatabase& database = test::threeSessions().database;
  const fs::path dir = test::freshTempDir("objects_file_store");
  const fs::path path = dir / "map.sqlite";
  {
    store::Store store(path.string());
    ObjectDatabase none;
    EXPECT_FALSE(loadObjectDatabase(store, none));
    saveObjectDatabase(ObjectDatabase{}, store);
    saveObjectDatabase(database, store);  // replaces the first copy
  }
  store::Store store(path.string(), {false, 0});
  ObjectDatabase loaded;
  ASSERT_TRUE(loadObjectDatabase(store, loaded));
  expectSameDatabase(database, loaded);
  // A copy written by a newer build is refused naming the map and both versions.
  const std::optional<store::ObjectDatabaseBlob> blob = store.objectDatabase();
  ASSERT_TRUE(blob.has_value());
  store.setObjectDatabase({3, blob->bytes});
  const std::string message = inputErrorOf([&] { loadObjectDatabase(store, loaded); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("format version 3; this build reads up to 2"), std::string::npos)
      << message;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace strata::objects

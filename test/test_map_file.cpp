// Map files: deterministic round trip, refusal of corrupted and truncated files, device upload;
// a mapper state (format version 2): round trip, what plain readers see, records that lie.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "fusion_fixture.h"
#include "strata/map/map_file.h"
#include "map_compare.h"
#include "strata/sim/analytic_dataset.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

class MapFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("strata_map_file_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    sim::AnalyticDatasetConfig config;
    config.frame_count = 4;
    const sim::AnalyticDataset dataset(config);
    map_ = test::fuseOnDevice(dataset, MapConfig{}, 4);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
  TsdfMap map_{MapConfig{}};
};

TEST_F(MapFileTest, SaveLoadSaveGivesIdenticalBytes) {
  saveMap(map_, path("a.strata"));
  const TsdfMap loaded = loadMap(path("a.strata"));
  saveMap(loaded, path("b.strata"));
  EXPECT_EQ(readFile(path("a.strata")), readFile(path("b.strata")));
  EXPECT_EQ(loaded.blockCount(), map_.blockCount());
  EXPECT_GT(loaded.blockCount(), 100u);
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().string().find(".tmp."), std::string::npos) << "temporary file left";
  }
}

TEST_F(MapFileTest, CorruptedFileIsRefused) {
  std::vector<std::uint8_t> bytes = serializeMap(map_);
  bytes[bytes.size() / 2] ^= 0x40;
  writeFileAtomically(path("bad.strata"), bytes);
  try {
    loadMap(path("bad.strata"));
    FAIL() << "a corrupted map was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("checksum"), std::string::npos) << e.what();
  }
}

TEST_F(MapFileTest, TruncatedFileIsRefused) {
  std::vector<std::uint8_t> bytes = serializeMap(map_);
  for (std::size_t keep : {std::size_t{0}, std::size_t{5}, std::size_t{30}, bytes.size() / 3,
                           bytes.size() - 1}) {
    std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(keep));
    EXPECT_THROW(deserializeMap(cut, "cut"), InputError) << "kept " << keep << " bytes";
  }
}

TEST_F(MapFileTest, MissingFileAndWrongVersionAreRefused) {
  EXPECT_THROW(loadMap(path("missing.strata")), InputError);
  std::vector<std::uint8_t> bytes = serializeMap(map_);
  bytes[8] = 99;  // format version
  try {
    deserializeMap(bytes, "v99");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("version"), std::string::npos) << e.what();
  }
}

TEST_F(MapFileTest, UnwritablePathFailsWithoutTouchingTheOldFile) {
  EXPECT_THROW(saveMap(map_, path("no/such/dir/map.strata")), Error);
}

TEST_F(MapFileTest, AMapperStateRoundTripsAndPlainReadersSeeItsLiveLayer) {
  TsdfMap static_map = map_;
  static_map.allocateBlock(BlockIndex(40, 40, 40))[0] = {0.01f, 3.0f, 0u};  // only S has it
  MapSessionRecord record;
  record.sessions_ended = 2;
  record.session_open = true;
  record.session_frames = 4;
  record.frames = 30;
  saveMapFile(MapFileContents{map_, static_map, record}, path("state.strata"));
  const MapFileContents loaded = loadMapFile(path("state.strata"));
  ASSERT_TRUE(loaded.sessions.has_value());
  EXPECT_EQ(loaded.sessions->sessions_ended, 2u);
  EXPECT_TRUE(loaded.sessions->session_open);
  EXPECT_EQ(loaded.sessions->session_frames, 4u);
  EXPECT_EQ(loaded.sessions->frames, 30u);
  ASSERT_TRUE(loaded.static_map.has_value());
  EXPECT_EQ(serializeMap(*loaded.static_map), serializeMap(static_map));
  EXPECT_EQ(serializeMap(loaded.map), serializeMap(map_));
  saveMapFile(loaded, path("again.strata"));
  EXPECT_EQ(readFile(path("state.strata")), readFile(path("again.strata")));
  EXPECT_EQ(readFile(path("state.strata"))[8], 2) << "format version 2";

  // Readers of plain maps see layer 1, the live layer.
  EXPECT_EQ(serializeMap(loadMap(path("state.strata"))), serializeMap(map_));
  // A plain map stays version 1, without a record.
  saveMap(map_, path("plain.strata"));
  EXPECT_EQ(readFile(path("plain.strata"))[8], 1);
  const MapFileContents plain = loadMapFile(path("plain.strata"));
  EXPECT_FALSE(plain.sessions.has_value());
  EXPECT_FALSE(plain.static_map.has_value());
}

TEST_F(MapFileTest, AMapperStateAtOddsWithItsRecordIsRefused) {
  MapSessionRecord record;
  record.sessions_ended = 1;
  EXPECT_THROW(serializeMapFile(MapFileContents{map_, map_, record}), InputError)
      << "a static layer without an open session";
  record.session_open = true;
  EXPECT_THROW(serializeMapFile(MapFileContents{map_, std::nullopt, record}), InputError)
      << "an open session without its static layer";

  // A record that says "open" over a file of one layer (checksum made to fit).
  record.session_open = false;
  std::vector<std::uint8_t> bytes = serializeMapFile(MapFileContents{map_, std::nullopt, record});
  constexpr std::size_t kOpenFlagAt = 8 + 4 + 4 + 60 + 4 + 4;  // magic .. sessions_ended
  bytes[kOpenFlagAt] = 1;
  const std::uint32_t crc = crc32(bytes.data(), bytes.size() - 4);
  std::memcpy(bytes.data() + bytes.size() - 4, &crc, 4);
  try {
    deserializeMapFile(bytes, "lying.strata");
    FAIL() << "a record at odds with the layers was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("lying.strata' holds 1 layers"), std::string::npos)
        << e.what();
  }
  bytes[kOpenFlagAt] = 7;
  const std::uint32_t crc7 = crc32(bytes.data(), bytes.size() - 4);
  std::memcpy(bytes.data() + bytes.size() - 4, &crc7, 4);
  EXPECT_THROW(deserializeMapFile(bytes, "flag7.strata"), InputError) << "a flag neither 0 nor 1";
}

TEST_F(MapFileTest, DeviceUploadRoundTrip) {
  DeviceTsdfMap device(test::sharedContext(), map_.config());
  device.upload(map_);
  TsdfMap back(map_.config());
  device.download(back);
  EXPECT_EQ(serializeMap(back), serializeMap(map_));
}

}  // namespace
}  // namespace strata

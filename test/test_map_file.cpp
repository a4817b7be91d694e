// Map files: deterministic round trip, refusal of corrupted and truncated files, device upload.
#include <gtest/gtest.h>

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

TEST_F(MapFileTest, DeviceUploadRoundTrip) {
  DeviceTsdfMap device(test::sharedContext(), map_.config());
  device.upload(map_);
  TsdfMap back(map_.config());
  device.download(back);
  EXPECT_EQ(serializeMap(back), serializeMap(map_));
}

}  // namespace
}  // namespace strata

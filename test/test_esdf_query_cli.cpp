// The ESDF slice picture and the CLI: `strata esdf` on a saved map and on a missing one,
// `strata fuse --esdf-png`.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "cli/esdf_command.h"
#include "cli/esdf_slice.h"
#include "cli/fuse_command.h"
#include "strata/core/error.h"
#include "esdf_sphere_scene.h"
#include "strata/io/image_io.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

class EsdfCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // The process id keeps concurrent runs of this test (other build folders) apart.
    dir_ = fs::temp_directory_path() /
           ("strata_esdf_" + std::to_string(::getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  /// Fuses a few frames of the built-in scene at 5 cm (optionally with --esdf-png).
  int fuse(const std::string& map_name, const std::string& esdf_png = "") {
    apps::FuseOptions options;
    options.map.voxel_size_m = 0.05f;
    options.frames = 6;
    options.map_path = path(map_name);
    options.esdf_png_path = esdf_png;
    options.slice_z_m = 0.5f;
    options.quiet = true;
    testing::internal::CaptureStdout();
    const int code = apps::runFuse(options);
    fuse_stdout_ = testing::internal::GetCapturedStdout();
    return code;
  }

  int esdf(const apps::EsdfOptions& options) {
    testing::internal::CaptureStdout();
    testing::internal::CaptureStderr();
    const int code = apps::runEsdf(options);
    stdout_ = testing::internal::GetCapturedStdout();
    stderr_ = testing::internal::GetCapturedStderr();
    return code;
  }

  fs::path dir_;
  std::string stdout_, stderr_, fuse_stdout_;
};

apps::Rgb pixelAt(const ColorImage& image, int x, int y) {
  const std::size_t i = (static_cast<std::size_t>(y) * image.width_px + x) * 3;
  return {{image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]}};
}

TEST_F(EsdfCliTest, SlicePngHasTheExpectedSizeAndColours) {
  const test::SphereEsdfScene& scene = test::sphereEsdfScene();
  apps::EsdfSliceOptions options;
  options.z_m = 1.0f;  // the layer with the unallocated block (2, 2, 2)
  options.min_map_px = 480;
  const apps::EsdfSlice slice = apps::renderEsdfSlice(scene.map, options);
  EXPECT_EQ(slice.stats.width_voxels, 48);
  EXPECT_EQ(slice.stats.height_voxels, 48);
  EXPECT_EQ(slice.stats.pixels_per_voxel, 10);  // 480 px over 48 voxels
  EXPECT_EQ(slice.stats.outside, 64u);          // one block missing
  EXPECT_EQ(slice.stats.unknown, 2u * 48u);     // the slab x = 14, 15
  EXPECT_GE(slice.image.width_px, 480 + 24);    // map plus colour bar
  EXPECT_GE(slice.image.height_px, 480);
  const std::string png = path("slice.png");
  apps::writeEsdfSlicePng(png, scene.map, options);
  const ColorImage read = readColorImage(png);
  EXPECT_EQ(read.width_px, slice.image.width_px);
  EXPECT_EQ(read.height_px, slice.image.height_px);
  EXPECT_EQ(read.rgb, slice.image.rgb);
  // Map pixel of voxel (gx, gy) of the grid (origin at voxel -24, y up): 12 px margin, title.
  const int top = 12 + 14 + 12;
  auto voxelPixel = [&](int gx, int gy) {
    return pixelAt(read, 12 + gx * 10 + 5, top + (47 - gy) * 10 + 5);
  };
  EXPECT_EQ(voxelPixel(46, 46), apps::kNoBlockColour);  // block (2, 2)
  const apps::Rgb slab = voxelPixel(24 + 14, 3);
  EXPECT_TRUE(slab == apps::kUnknownHatch[0] || slab == apps::kUnknownHatch[1]);
  EXPECT_EQ(voxelPixel(0, 0),
            apps::esdfColour((slice.stats.max_distance_m - slice.stats.colour_min_m) /
                             (slice.stats.colour_max_m - slice.stats.colour_min_m)));
}

TEST_F(EsdfCliTest, SliceOutsideTheMapNamesTheRange) {
  apps::EsdfSliceOptions options;
  options.z_m = 5.0f;
  try {
    apps::renderEsdfSlice(test::sphereEsdfScene().map, options);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("covers z from -1.2 to 1.2"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(apps::renderEsdfSlice(EsdfMap{}, apps::EsdfSliceOptions{}), InputError);
}

TEST_F(EsdfCliTest, MissingMapFileExitsNonZeroNamingIt) {
  apps::EsdfOptions options;
  options.map_path = path("no_such_map.strata");
  options.png_path = path("out.png");
  EXPECT_NE(esdf(options), 0);
  EXPECT_NE(stderr_.find("no_such_map.strata"), std::string::npos) << stderr_;
  EXPECT_FALSE(fs::exists(options.png_path));
}

TEST_F(EsdfCliTest, SavedMapGivesSliceAndSummary) {
  ASSERT_EQ(fuse("map.strata"), 0);
  apps::EsdfOptions options;
  options.map_path = path("map.strata");
  options.png_path = path("slice.png");
  options.slice_z_m = 0.5f;
  options.voxel_size_check = true;
  EXPECT_EQ(esdf(options), 0) << stderr_;
  EXPECT_TRUE(fs::exists(options.png_path));
  EXPECT_NE(stdout_.find("ms device time"), std::string::npos) << stdout_;
  EXPECT_NE(stdout_.find("Wrote " + options.png_path), std::string::npos) << stdout_;
  EXPECT_NE(stdout_.find(": ok."), std::string::npos) << stdout_;
  options.slice_z_m = 50.0f;  // no block there: a picture cannot be made
  EXPECT_EQ(esdf(options), 2);
  EXPECT_NE(stderr_.find("no ESDF block holds z = 50"), std::string::npos) << stderr_;
}

TEST_F(EsdfCliTest, FuseKeepsTheEsdfAndWritesTheSlice) {
  EXPECT_EQ(fuse("map.strata", path("fused_slice.png")), 0);
  EXPECT_TRUE(fs::exists(path("fused_slice.png")));
  EXPECT_NE(fuse_stdout_.find("ESDF kept up to date incrementally"), std::string::npos)
      << fuse_stdout_;
}

}  // namespace
}  // namespace strata

// The limits every reader of outside data checks before it allocates (docs/fuzzing.md): an input
// just over each one is refused with an InputError that names the limit. Oversized files are
// sparse, so the tests take no disk space or time.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "strata/core/error.h"
#include "strata/core/image_limits.h"
#include "strata/io/camera_model.h"
#include "strata/io/image_io.h"
#include "strata/io/seven_scenes_dataset.h"
#include "strata/io/tum_format.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_image.h"
#include "strata/map/map_file.h"
#include "strata/mesh/mesh_file_limits.h"
#include "strata/mesh/ply.h"
#include "strata/sim/world/mesh_file.h"

namespace strata {
namespace {

namespace fs = std::filesystem;

void expectRefused(const std::function<void()>& read, const std::string& limit_name) {
  try {
    read();
    ADD_FAILURE() << "accepted; expected an InputError naming " << limit_name;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(limit_name), std::string::npos) << e.what();
  }
}

class InputLimits : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("strata_limits_" + std::to_string(getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A sparse file of `bytes` bytes (no disk blocks): only its size matters to the checks.
  std::string sparseFile(const std::string& name, std::uint64_t bytes) const {
    const fs::path path = dir_ / name;
    std::ofstream(path).put('x');
    fs::resize_file(path, bytes);
    return path.string();
  }

  fs::path dir_;
};

constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;

TEST_F(InputLimits, FilesOverTheirSizeLimitAreRefusedBeforeReading) {
  expectRefused([&] { loadMap(sparseFile("m.strata", (std::uint64_t{8} << 30) + 1)); },
                "kMaxMapFileBytes");
  const std::uint64_t mesh_bytes = kMaxMeshFileBytes.max_bytes + 1;
  expectRefused([&] { readPly(sparseFile("m.ply", mesh_bytes)); }, "kMaxMeshFileBytes");
  expectRefused([&] { sim::readObj(sparseFile("m.obj", mesh_bytes)); }, "kMaxMeshFileBytes");
  const std::string tum_file = sparseFile("groundtruth.txt", 256 * kMiB + 1);
  expectRefused([&] { tum::readTrajectory(tum_file); }, "kMaxTumTextFileBytes");
  expectRefused([&] { tum::readFileList(tum_file); }, "kMaxTumTextFileBytes");
  expectRefused([&] { readPoseMatrixFile(sparseFile("p.pose.txt", 64 * 1024 + 1)); },
                "kMaxPoseFileBytes");
  CameraModel model;
  const std::string camera_file = sparseFile("camera.yaml", kMiB + 1);
  expectRefused([&] { applyCameraYaml(camera_file, &model); }, "kMaxCameraFileBytes");
  expectRefused([&] { applyIntrinsicsMatrixFile(camera_file, &model); }, "kMaxCameraFileBytes");
  const std::string image_file = sparseFile("d.png", 256 * kMiB + 1);
  expectRefused([&] { readDepthPng(image_file, DepthDecoder(5000.0, {0})); },
                "kMaxImageFileBytes");
  expectRefused([&] { readColorImage(image_file); }, "kMaxImageFileBytes");
}

/// A PNG of only a signature and an IHDR (16-bit grey), padded to `file_bytes`.
std::vector<std::uint8_t> pngHeader(std::uint32_t width, std::uint32_t height,
                                    std::size_t file_bytes = 64) {
  std::vector<std::uint8_t> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n', 0, 0, 0, 13,
                                   'I',  'H', 'D', 'R'};
  for (std::uint32_t v : {width, height}) {
    for (int shift = 24; shift >= 0; shift -= 8) png.push_back((v >> shift) & 0xFF);
  }
  for (std::uint8_t b : {16, 0, 0, 0, 0, 0, 0, 0, 0}) png.push_back(b);  // depth, type, ..., CRC
  png.resize(std::max(file_bytes, png.size()), 0);
  return png;
}

TEST_F(InputLimits, ImageHeadersOverTheSizeLimitsAreRefusedBeforeDecoding) {
  const DepthDecoder decoder(5000.0, {0});
  const int side = kMaxImageSidePx + 1;
  expectRefused([&] { decodeDepthPng(pngHeader(side, 1), "d.png", decoder); }, "kMaxImageSidePx");
  expectRefused([&] { decodeDepthPng(pngHeader(1u << 31, 1), "d.png", decoder); },
                "kMaxImageSidePx");
  expectRefused([&] { decodeColorImage(pngHeader(1, side), "c.png"); }, "kMaxImageSidePx");
  // Sides within the limit, pixels just over it (8193 x 8192 > 2^26).
  expectRefused([&] { decodeDepthPng(pngHeader(8193, 8192, 8 * kMiB), "d.png", decoder); },
                "kMaxImagePixels");
  // 1000 x 1000 16-bit pixels cannot fit 64 bytes even at deflate's best ratio.
  expectRefused([&] { decodeDepthPng(pngHeader(1000, 1000), "d.png", decoder); },
                "kMaxDeflateRatio");
  // A JPEG whose frame header (SOF0) claims 16385 x 8.
  const std::vector<std::uint8_t> jpeg = {0xFF, 0xD8, 0xFF, 0xC0, 0x00, 0x11, 0x08, 0x00, 0x08,
                                          0x40, 0x01, 0x03, 0x01, 0x22, 0x00, 0x02, 0x11, 0x01};
  expectRefused([&] { decodeColorImage(jpeg, "c.jpg"); }, "kMaxImageSidePx");
  expectRefused([&] { decodeColorImage({'B', 'M', 0, 0, 0, 0}, "c.bmp"); }, "not a PNG or JPEG");
}

TEST_F(InputLimits, PlyHeadersOverTheMeshLimitsAreRefusedBeforeReading) {
  const std::string vertices = "ply\nformat ascii 1.0\nelement vertex " +
                               std::to_string(kMaxMeshVertices + 1) +
                               "\nproperty float x\nproperty float y\nproperty float z\n"
                               "end_header\n";
  expectRefused([&] { parsePly(vertices, "v.ply"); }, "kMaxMeshVertices");
  const std::string faces = "ply\nformat binary_little_endian 1.0\nelement face " +
                            std::to_string(kMaxMeshTriangles + 1) +
                            "\nproperty list uchar int vertex_indices\nend_header\n";
  expectRefused([&] { parsePly(faces, "f.ply"); }, "kMaxMeshTriangles");
}

TEST_F(InputLimits, LcmPayloadsAndImagesOverTheLimitsAreRefusedBeforeDecoding) {
  const std::vector<std::uint8_t> payload(static_cast<std::size_t>(lcm_io::kMaxPayloadBytes) + 1);
  rgbd_frame_t frame;
  expectRefused(
      [&] { lcm_io::decodePayload(payload.data(), static_cast<int>(payload.size()), frame); },
      "kMaxPayloadBytes");
  image_t image{};
  image.encoding = lcm_io::kDepth16;
  image.depth_scale = 5000.0f;
  image.width = kMaxImageSidePx + 1;
  image.height = 1;
  expectRefused([&] { lcm_io::decodeDepth(image); }, "kMaxImageSidePx");
  image.width = 8193;
  image.height = 8192;
  expectRefused([&] { lcm_io::decodeDepth(image); }, "kMaxImagePixels");
  image.encoding = lcm_io::kRgb8;
  expectRefused([&] { lcm_io::decodeColor(image); }, "kMaxImagePixels");
}

}  // namespace
}  // namespace strata

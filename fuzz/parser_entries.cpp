#include "parser_entries.h"

#include <algorithm>
#include <cstring>
#include <sstream>
#include <utility>

#include "strata/core/atomic_file.h"
#include "strata/io/camera_model.h"
#include "strata/io/euroc_parse.h"
#include "strata/io/image_io.h"
#include "strata/io/seven_scenes_dataset.h"
#include "strata/io/tum_format.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/convert_stereo.h"
#include "strata/map/map_file.h"
#include "strata/mesh/ply.h"
#include "strata/objects/object_database_file.h"
#include "strata/sim/world/mesh_file.h"
#include "strata/sim/world/world_parser.h"
#include "strata/command_t.hpp"

namespace strata::fuzz {
namespace {

std::string text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

std::vector<std::uint8_t> bytes(const std::uint8_t* data, std::size_t size) {
  return std::vector<std::uint8_t>(data, data + size);
}

/// NOTE: the trailing CRC-32 is recomputed, so inputs reach the config, layer and block parsing
/// behind the checksum instead of nearly all stopping at it.
void mapFile(const std::uint8_t* data, std::size_t size) {
  std::vector<std::uint8_t> file = bytes(data, size);
  if (file.size() >= 4) {
    const std::uint32_t crc = crc32(file.data(), file.size() - 4);
    std::memcpy(file.data() + file.size() - 4, &crc, 4);
  }
  deserializeMapFile(file, "fuzz.strata");  // both versions: a plain map and a mapper state
}

/// Object database files (objects/object_database_file.h). NOTE: the header's payload size and
/// FNV-1a checksum are rewritten to fit the input, so inputs reach the payload's parsing (sessions,
/// instances, each model's map-file TSDF) instead of nearly all stopping at the header.
void objectDatabase(const std::uint8_t* data, std::size_t size) {
  constexpr std::size_t kSizeAt = 9 + 4;  // magic "STRATAOBJ", u32 version
  constexpr std::size_t kChecksumAt = kSizeAt + 4;
  constexpr std::size_t kHeaderBytes = kChecksumAt + 8;
  std::string file = text(data, size);
  if (file.size() >= kHeaderBytes) {
    const auto payload = static_cast<std::uint32_t>(file.size() - kHeaderBytes);
    std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bit
    for (std::size_t i = kHeaderBytes; i < file.size(); ++i) {
      hash ^= static_cast<std::uint8_t>(file[i]);
      hash *= 1099511628211ull;
    }
    std::memcpy(&file[kSizeAt], &payload, sizeof(payload));
    std::memcpy(&file[kChecksumAt], &hash, sizeof(hash));
  }
  objects::deserializeObjectDatabase(file, "fuzz.objects");
}

void tumFileList(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(text(data, size));
  tum::readFileList(in, "depth.txt");
}

void tumTrajectory(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(text(data, size));
  tum::readTrajectory(in, "groundtruth.txt");
}

void poseMatrix(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(text(data, size));
  readPoseMatrix(in, "frame.pose.txt");
}

/// Applied then validated, as resolveCameraModel does, and turned into the depth decoder.
void cameraYaml(const std::uint8_t* data, std::size_t size) {
  CameraModel model;
  applyCameraYamlText(text(data, size), "camera.yaml", &model);
  model.validate();
  DepthDecoder decoder(model.depth_scale, model.depth_invalid);
}

void intrinsicsMatrix(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(text(data, size));
  CameraModel model;
  applyIntrinsicsMatrix(in, "camera-intrinsics.txt", &model);
  model.validate();
}

void depthPng(const std::uint8_t* data, std::size_t size) {
  static const DepthDecoder kDecoder(5000.0, {0});
  decodeDepthPng(bytes(data, size), "depth.png", kDecoder);
}

void colorImage(const std::uint8_t* data, std::size_t size) {
  decodeColorImage(bytes(data, size), "color.png");
}

/// Mesh paths resolve against a folder that does not exist: inputs reach the file system only as
/// an existence check.
void worldYaml(const std::uint8_t* data, std::size_t size) {
  sim::parseWorldSpec(text(data, size), "world.yaml", "/nonexistent-strata-fuzz");
}

void objMesh(const std::uint8_t* data, std::size_t size) {
  std::istringstream in(text(data, size));
  sim::readObj(in, "mesh.obj");
}

void plyMesh(const std::uint8_t* data, std::size_t size) { parsePly(text(data, size), "mesh.ply"); }

template <typename Message>
Message decoded(const std::uint8_t* data, std::size_t size) {
  Message message;
  lcm_io::decodePayload(data, static_cast<int>(size), message);
  return message;
}

// The LCM entries do what strata-mapper's handlers do with a payload (apps/mapper_node).
void lcmRgbdFrame(const std::uint8_t* data, std::size_t size) {
  lcm_io::decodeFrame(decoded<rgbd_frame_t>(data, size));
}

void lcmCameraInfo(const std::uint8_t* data, std::size_t size) {
  lcm_io::decodeCameraInfo(decoded<camera_info_t>(data, size));
}

void lcmPose(const std::uint8_t* data, std::size_t size) {
  lcm_io::decodePose(decoded<pose_t>(data, size));
}

void lcmCommand(const std::uint8_t* data, std::size_t size) { decoded<command_t>(data, size); }

/// EuRoC sensor.yaml: the IMU's when it says so, else a camera's (what the reader does per folder).
void eurocSensorYaml(const std::uint8_t* data, std::size_t size) {
  const std::string yaml = text(data, size);
  if (yaml.find("sensor_type: imu") != std::string::npos) {
    euroc::parseImuYaml(yaml, "imu0/sensor.yaml");
  } else {
    euroc::parseCameraYaml(yaml, "cam0/sensor.yaml");
  }
}

/// EuRoC csv files, told apart by the first data row's column count: 2 a camera's data.csv, 7 the
/// IMU's, otherwise the ground truth's.
void eurocCsv(const std::uint8_t* data, std::size_t size) {
  const std::string csv = text(data, size);
  std::size_t line = 0;
  while (line < csv.size() && csv[line] == '#') {
    const std::size_t end = csv.find('\n', line);
    line = end == std::string::npos ? csv.size() : end + 1;
  }
  const std::size_t end = std::min(csv.find('\n', line), csv.size());
  const auto commas = std::count(csv.begin() + static_cast<std::ptrdiff_t>(line),
                                 csv.begin() + static_cast<std::ptrdiff_t>(end), ',');
  if (commas == 1) {
    euroc::parseImageCsv(csv, "cam0/data.csv");
  } else if (commas == 6) {
    euroc::parseImuCsv(csv, "imu0/data.csv");
  } else {
    euroc::parseGroundTruthCsv(csv, "state_groundtruth_estimate0/data.csv");
  }
}

// What a consumer of STRATA_STEREO / STRATA_IMU does with a payload.
void lcmStereoImage(const std::uint8_t* data, std::size_t size) {
  lcm_io::decodeStereo(decoded<stereo_image_t>(data, size));
}

void lcmImu(const std::uint8_t* data, std::size_t size) {
  lcm_io::decodeImu(decoded<imu_t>(data, size));
}

const std::pair<const char*, Entry> kEntries[] = {
    {"fuzz_map_file", mapFile},
    {"fuzz_tum_file_list", tumFileList},
    {"fuzz_tum_trajectory", tumTrajectory},
    {"fuzz_pose_matrix", poseMatrix},
    {"fuzz_camera_yaml", cameraYaml},
    {"fuzz_intrinsics_matrix", intrinsicsMatrix},
    {"fuzz_depth_png", depthPng},
    {"fuzz_color_image", colorImage},
    {"fuzz_world_yaml", worldYaml},
    {"fuzz_obj_mesh", objMesh},
    {"fuzz_ply_mesh", plyMesh},
    {"fuzz_lcm_rgbd_frame", lcmRgbdFrame},
    {"fuzz_lcm_camera_info", lcmCameraInfo},
    {"fuzz_lcm_pose", lcmPose},
    {"fuzz_lcm_command", lcmCommand},
    {"fuzz_euroc_sensor_yaml", eurocSensorYaml},
    {"fuzz_euroc_csv", eurocCsv},
    {"fuzz_lcm_stereo_image", lcmStereoImage},
    {"fuzz_lcm_imu", lcmImu},
    {"fuzz_object_database", objectDatabase},
};

}  // namespace

Entry findEntry(const std::string& name) {
  for (const auto& [entry_name, entry] : kEntries) {
    if (name == entry_name) return entry;
  }
  return nullptr;
}

std::vector<std::string> entryNames() {
  std::vector<std::string> names;
  for (const auto& entry : kEntries) names.emplace_back(entry.first);
  return names;
}

}  // namespace strata::fuzz

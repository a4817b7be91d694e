// strata_fuzz_seeds <folder>: writes the seed corpus, <folder>/<target>/seed_*, with the project's
// own writers and encoders, so every seed is a small valid input (the committed fuzz/corpus/ comes
// from this program; regenerate it after a format change).
#include <filesystem>
#include <fstream>
#include <iostream>

#include "strata/io/euroc_writer.h"
#include "strata/io/image_io.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_image.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/convert_stereo.h"
#include "strata/map/map_file.h"
#include "strata/mesh/ply.h"
#include "strata/objects/object_database_file.h"
#include "strata/command_t.hpp"

namespace strata {
namespace {

namespace fs = std::filesystem;

void writeBytes(const fs::path& path, const void* data, std::size_t size) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary).write(static_cast<const char*>(data), size);
}

void writeText(const fs::path& path, const std::string& text) {
  writeBytes(path, text.data(), text.size());
}

template <typename Message>
void writeMessage(const fs::path& path, const Message& message) {
  std::vector<std::uint8_t> bytes(message.getEncodedSize());
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  writeBytes(path, bytes.data(), bytes.size());
}

RgbdFrame smallFrame() {
  RgbdFrame frame;
  frame.depth = DepthImage(4, 3, 1.25f);
  frame.depth.depth_m[5] = 0.0f;
  frame.color = ColorImage(4, 3, 90);
  frame.T_W_C.translation() = Eigen::Vector3d(0.5, -1.0, 0.25);
  return frame;
}

Mesh smallMesh() {
  Mesh mesh;
  mesh.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  mesh.triangles = {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}};
  return mesh;
}

void writeMapSeeds(const fs::path& out) {
  TsdfMap map(MapConfig{});
  TsdfBlock& block = map.allocateBlock(BlockIndex(1, -2, 3));
  for (std::size_t i = 0; i < block.size(); ++i) block[i] = {0.01f * (i % 7), 1.0f, 0x203040u};
  const std::vector<std::uint8_t> bytes = serializeMap(map);
  writeBytes(out / "fuzz_map_file/seed_one_block.strata", bytes.data(), bytes.size());
  const std::vector<std::uint8_t> empty = serializeMap(TsdfMap(MapConfig{}));
  writeBytes(out / "fuzz_map_file/seed_empty.strata", empty.data(), empty.size());
  // A mapper state with a session open: the record and both layers (format version 2).
  MapSessionRecord record;
  record.sessions_ended = 2;
  record.session_open = true;
  record.session_frames = 3;
  record.frames = 40;
  const std::vector<std::uint8_t> state = serializeMapFile(MapFileContents{map, map, record});
  writeBytes(out / "fuzz_map_file/seed_mapper_state.strata", state.data(), state.size());
}

/// An empty database, and one with a model of one block and two instances.
void writeObjectDatabaseSeeds(const fs::path& out) {
  fs::create_directories(out / "fuzz_object_database");
  const std::string empty = objects::serializeObjectDatabase(objects::ObjectDatabase{});
  writeBytes(out / "fuzz_object_database/seed_empty.objects", empty.data(), empty.size());
  objects::ObjectModel model;
  model.id = 1;
  model.merged_observations = 2;
  TsdfBlock& block = model.tsdf.allocateBlock(BlockIndex(0, -1, 0));
  for (std::size_t i = 0; i < block.size(); ++i) {
    block[i] = {0.02f * static_cast<float>(i % 9) - 0.08f, 2.0f, 0x506070u};
  }
  for (int session = 0; session < 2; ++session) {
    objects::ObjectInstance instance;
    instance.session = session;
    instance.segment_id = 1;
    instance.T_W_M.translation() = Eigen::Vector3d(1.0 + session, 2.0, 0.0);
    instance.merged = true;
    model.instances.push_back(instance);
  }
  const objects::ObjectDatabase database =
      objects::ObjectDatabase::fromParts(objects::DatabaseConfig{}, {std::move(model)}, {0, 1});
  const std::string bytes = objects::serializeObjectDatabase(database);
  writeBytes(out / "fuzz_object_database/seed_one_model.objects", bytes.data(), bytes.size());
}

void writeMeshSeeds(const fs::path& out) {
  fs::create_directories(out / "fuzz_ply_mesh");
  writePly((out / "fuzz_ply_mesh/seed_binary.ply").string(), smallMesh());
  writeText(out / "fuzz_ply_mesh/seed_ascii.ply",
            "ply\nformat ascii 1.0\ncomment seed\nelement vertex 4\nproperty float x\n"
            "property float y\nproperty float z\nproperty uchar red\nproperty uchar green\n"
            "property uchar blue\nelement face 2\nproperty list uchar int vertex_indices\n"
            "end_header\n0 0 0 255 0 0\n1 0 0 0 255 0\n1 1 0 0 0 255\n0 1 0 9 9 9\n"
            "3 0 1 2\n4 0 1 2 3\n");
  writeText(out / "fuzz_obj_mesh/seed_tetra.obj",
            "# tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvn 0 0 1\nvt 0 0\n"
            "f 1 2 3\nf 1/1 2/1 4/1\nf 1//1 3//1 4//1\nf -4 -3 -2 -1\n");
}

void writeImageSeeds(const fs::path& out) {
  const RgbdFrame frame = smallFrame();
  fs::create_directories(out / "fuzz_depth_png");
  fs::create_directories(out / "fuzz_color_image");
  writeDepthPng((out / "fuzz_depth_png/seed_4x3.png").string(), frame.depth, 5000.0);
  writeColorPng((out / "fuzz_color_image/seed_4x3.png").string(), frame.color);
  writeColorPng((out / "fuzz_color_image/seed_4x3.jpg").string(), frame.color);
}

void writeLcmSeeds(const fs::path& out) {
  const RgbdFrame frame = smallFrame();
  lcm_io::FrameEncoding encoding;
  writeMessage(out / "fuzz_lcm_rgbd_frame/seed_depth16.lcm",
               lcm_io::encodeFrame(frame, 1000, "cam0", 1, encoding));
  encoding.depth = lcm_io::kDepth32f;
  encoding.with_pose = false;
  writeMessage(out / "fuzz_lcm_rgbd_frame/seed_depth32f.lcm",
               lcm_io::encodeFrame(frame, 2000, "cam0", 2, encoding));
  CameraIntrinsics k;
  k.width_px = 4;
  k.height_px = 3;
  writeMessage(out / "fuzz_lcm_camera_info/seed_none.lcm",
               lcm_io::encodeCameraInfo(k, "cam0", 1000));
  camera_info_t plumb_bob = lcm_io::encodeCameraInfo(k, "cam0", 1000);
  plumb_bob.distortion_model = "plumb_bob";
  plumb_bob.num_distortion = 5;
  plumb_bob.distortion.assign(5, 0.0);
  writeMessage(out / "fuzz_lcm_camera_info/seed_plumb_bob.lcm", plumb_bob);
  writeMessage(out / "fuzz_lcm_pose/seed_pose.lcm", lcm_io::encodePose(frame.T_W_C, 1000));
  command_t command{};
  command.utime = 1000;
  command.request_id = 7;
  command.command = command_t::SAVE_MAP;
  command.argument = "/tmp/map.strata";
  writeMessage(out / "fuzz_lcm_command/seed_save_map.lcm", command);
}

void writeTextSeeds(const fs::path& out) {
  writeText(out / "fuzz_tum_file_list/seed_depth.txt",
            "# depth maps\n# file: 'rgbd_dataset'\n# timestamp filename\n"
            "1305031102.160407 depth/1305031102.160407.png\n"
            "1305031102.194330 depth/1305031102.194330.png\n");
  writeText(out / "fuzz_tum_trajectory/seed_groundtruth.txt",
            "# ground truth trajectory\n# timestamp tx ty tz qx qy qz qw\n"
            "1305031098.6659 1.3563 0.6305 1.6380 0.6132 0.5962 -0.3311 -0.3986\n"
            "1305031098.6758 1.3543 0.6306 1.6360 0.6129 0.5966 -0.3316 -0.3980\n");
  writeText(out / "fuzz_pose_matrix/seed_pose.txt",
            " 9.9935108e-001 -2.9258777e-003  3.5994634e-002 -1.1701600e-001\n"
            " 2.7129020e-003  9.9998546e-001  4.3823677e-003  3.4216270e-002\n"
            "-3.6012352e-002 -4.2730211e-003  9.9934226e-001  1.5310720e-001\n"
            " 0.0000000e+000  0.0000000e+000  0.0000000e+000  1.0000000e+000\n");
  writeText(out / "fuzz_intrinsics_matrix/seed_k.txt",
            "5.8500000e+02 0.0000000e+00 3.2000000e+02\n"
            "0.0000000e+00 5.8500000e+02 2.4000000e+02\n"
            "0.0000000e+00 0.0000000e+00 1.0000000e+00\n");
  writeText(out / "fuzz_camera_yaml/seed_camera.yaml",
            "# TUM freiburg1\nwidth: 640\nheight: 480\nfx: 517.3\nfy: 516.5\ncx: 318.6\n"
            "cy: 255.3\ndepth_scale: 5000\ndepth_invalid: [0, 65535]\n");
  writeText(out / "fuzz_world_yaml/seed_room.yaml",
            "name: tiny\nseed: 3\nsessions: 2\nwall_thickness: 0.1\nrooms:\n"
            "  - {name: main, min: [0, 0], max: [4, 3], height: 2.5,\n"
            "     floor: {albedo: [150, 128, 100]}, walls: {albedo: [225, 222, 210]}}\n"
            "doors:\n  - {at: [4.05, 1.5], width: 0.9, height: 2.0}\n"
            "static:\n  - {name: pillar_a, type: pillar, radius: 0.15, at: [3, 1]}\n"
            "objects:\n  - {name: crate, type: box, size: [0.5, 0.4, 0.3], albedo: [200, 60, 40],"
            " at: [1, 1], yaw: 15}\n  - {name: chair_a, type: chair, at: [2, 2], yaw: 95}\n"
            "  - {name: bunny, type: mesh, file: data:meshes/bunny.obj, scale: 1.5, up: y,"
            " optional: true}\n"
            "pool:\n  - {name: table, type: table, size: [1.2, 0.7, 0.75]}\n"
            "placement: {regions: [{min: [0.3, 0.3], max: [3.7, 2.7]}], clearance: 0.1}\n"
            "changes: {move_probability: 0.25, remove_probability: 0.1, add: [0, 1],"
            " min_changes: 1}\n"
            "lighting: {direction: [0.3, -0.4, 1], intensity: 0.65, ambient: 0.35}\n");
}

void writeEurocSeeds(const fs::path& out) {
  euroc::CameraCalibration cam;
  cam.name = "cam0";
  cam.width_px = 752;
  cam.height_px = 480;
  cam.fu_px = 458.654;
  cam.fv_px = 457.296;
  cam.cu_px = 367.215;
  cam.cv_px = 248.375;
  cam.rate_hz = 20.0;
  cam.distortion = euroc::DistortionModel::kRadialTangential;
  cam.distortion_coefficients = {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05};
  cam.T_B_C.translation() = Eigen::Vector3d(-0.0216, -0.0647, 0.0098);
  writeText(out / "fuzz_euroc_sensor_yaml/seed_cam0.yaml", euroc::cameraYaml(cam));
  euroc::ImuCalibration imu;
  imu.rate_hz = 200.0;
  imu.gyro_noise_density = 1.6968e-04;
  imu.gyro_random_walk = 1.9393e-05;
  imu.accel_noise_density = 2.0e-3;
  imu.accel_random_walk = 3.0e-3;
  writeText(out / "fuzz_euroc_sensor_yaml/seed_imu0.yaml", euroc::imuYaml(imu));
  writeText(out / "fuzz_euroc_csv/seed_cam0.csv",
            "#timestamp [ns],filename\n1403715273262142976,1403715273262142976.png\n"
            "1403715273312143104,1403715273312143104.png\n");
  writeText(out / "fuzz_euroc_csv/seed_imu0.csv",
            "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
            "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n"
            "1403715273262142976,-0.0020943951023931952,0.017453292519943295,0.0774926187885,"
            "9.0874956666666655,0.13075533333333333,-3.6938381666666662\n"
            "1403715273267142912,-0.0013962634015954637,0.019547687622336492,0.0781907504893,"
            "9.0793234583333327,0.122583125,-3.6938381666666662\n");
  writeText(
      out / "fuzz_euroc_csv/seed_groundtruth.csv",
      "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], "
      "q_RS_z [], v_RS_R_x, v_RS_R_y, v_RS_R_z, b_w_x, b_w_y, b_w_z, b_a_x, b_a_y, b_a_z\n"
      "1403715273262142976,0.878895,2.1834,0.948427,0.069433,-0.824237,-0.106942,-0.551702,"
      "0.001,-0.002,0.0,-0.002,0.02,0.076,-0.01,0.1,0.08\n");
  GreyImage left(4, 3, 90), right(4, 3, 80);
  left.pixels[5] = 200;
  writeMessage(out / "fuzz_lcm_stereo_image/seed_stereo.lcm",
               lcm_io::encodeStereo(left, right, 1000, 3, "cam0", "cam1"));
  writeMessage(out / "fuzz_lcm_stereo_image/seed_mono.lcm",
               lcm_io::encodeStereo(left, {}, 1000, 0, "cam0", ""));
  writeMessage(out / "fuzz_lcm_imu/seed_imu.lcm",
               lcm_io::encodeImu({1000, "imu0", {0.01, -0.02, 0.5}, {0.1, 0.2, 9.81}}));
}

}  // namespace
}  // namespace strata

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: strata_fuzz_seeds <folder>\n";
    return 2;
  }
  const std::filesystem::path out(argv[1]);
  strata::writeMapSeeds(out);
  strata::writeObjectDatabaseSeeds(out);
  strata::writeMeshSeeds(out);
  strata::writeImageSeeds(out);
  strata::writeLcmSeeds(out);
  strata::writeTextSeeds(out);
  strata::writeEurocSeeds(out);
  return 0;
}

// strata-view's live scene (apps/view/live_view.h) fed over memq:// in-process: mesh blocks put
// and removed as the mapper sends them, the camera pose and trajectories, stats, objects, the ESDF
// slice and distance queries from it; corrupt messages counted and skipped. Last, a real
// strata-mapper in-process: the view shows the blocks and the block count it published.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "lcm_test_helpers.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/esdf_slice_msg.h"
#include "strata/lcm/lcm_time.h"
#include "strata/rgbd_frame_t.hpp"
#include "view/live_items.h"
#include "view/live_view.h"

namespace strata::test {
namespace {

using view::LiveView;

template <typename Message>
std::vector<std::uint8_t> encoded(const Message& m) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  return bytes;
}

/// A view on its own memq:// LCM object; the test publishes and dispatches on its thread.
struct Fixture {
  lcm::LCM lcm{"memq://"};
  view::Scene scene;
  view::LiveChannels channels;
  LiveView live{lcm, scene, channels, "test"};

  template <typename Message>
  void publish(const std::string& channel, const Message& m) {
    ASSERT_EQ(lcm.publish(channel, &m), 0);
  }
  void publishBytes(const std::string& channel, const std::vector<std::uint8_t>& bytes) {
    ASSERT_EQ(lcm.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size())), 0);
  }
  /// Dispatches everything published so far and puts the trajectories and stats.
  void drain() {
    while (live.handle(0) > 0) {
    }
    live.flush();
  }
  nlohmann::json header(const std::string& id) const {
    const view::Message m = scene.get(id);
    return m ? view::decodeMessage(*m).header : nlohmann::json();
  }
};

/// The ids of the mesh items a client connecting now would get.
std::set<std::string> meshIds(const view::Scene& scene) {
  std::vector<view::Message> messages;
  scene.changesSince(0, &messages);
  std::set<std::string> ids;
  for (const view::Message& m : messages) {
    const nlohmann::json h = view::decodeMessage(*m).header;
    if (h["type"] == "mesh") ids.insert(h["id"].get<std::string>());
  }
  return ids;
}

/// A block with one triangle (or none).
mesh_block_t block(int x, int y, int z, bool surface = true) {
  mesh_block_t b{};
  b.index[0] = x;
  b.index[1] = y;
  b.index[2] = z;
  if (surface) {
    b.vertices = {{0.4f * x, 0.4f * y, 0.4f * z},
                  {0.4f * x + 0.1f, 0.4f * y, 0.4f * z},
                  {0.4f * x, 0.4f * y + 0.1f, 0.4f * z}};
    b.colors = {{200, 10, 10}, {10, 200, 10}, {10, 10, 200}};
    b.triangles = {{0, 1, 2}};
  }
  b.num_vertices = static_cast<std::int32_t>(b.vertices.size());
  b.num_triangles = static_cast<std::int32_t>(b.triangles.size());
  return b;
}

mesh_update_t update(std::int64_t sequence, std::vector<mesh_block_t> blocks, bool full = false) {
  mesh_update_t u{};
  u.utime = lcm_io::nowUtime();
  u.sequence = sequence;
  u.full = full;
  u.voxel_size_m = 0.05f;
  u.blocks = std::move(blocks);
  u.num_blocks = static_cast<std::int32_t>(u.blocks.size());
  return u;
}

/// A 4 x 3 slice at z = 1 m, 0.1 m cells, cell (0, 0) centred at (0, 0); d = 0.1 c + 0.01 r,
/// cell (2, 3) unobserved.
esdf_slice_t slice() {
  esdf_slice_t s{};
  s.utime = lcm_io::nowUtime();
  s.z_m = 1.0f;
  s.resolution_m = 0.1f;
  s.width = 4;
  s.height = 3;
  s.distance_m.assign(3, std::vector<float>(4));
  s.state.assign(3, std::vector<std::int8_t>(4, lcm_io::kSliceObserved));
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 4; ++c) s.distance_m[r][c] = 0.1f * c + 0.01f * r;
  }
  s.state[2][3] = lcm_io::kSliceUnknown;
  s.distance_m[2][3] = std::nanf("");
  return s;
}

nlohmann::json query(LiveView& live, float x, float y, float z) {
  return view::decodeMessage(*live.answer({{"type", "query"}, {"id", 7}, {"point", {x, y, z}}}))
      .header;
}

TEST(ViewLive, MeshBlocksArePutAndTheBlocksTheMapperEmptiesAreRemoved) {
  Fixture f;
  const mesh_update_t first = update(0, {block(0, 0, 0), block(1, 0, 0)});
  f.publish(f.channels.mesh, first);
  f.drain();
  EXPECT_EQ(meshIds(f.scene), (std::set<std::string>{"block:0,0,0", "block:1,0,0"}));
  const nlohmann::json h = f.header("block:1,0,0");
  EXPECT_EQ(h["group"], "map");
  EXPECT_EQ(h["t_pub_us"].get<std::int64_t>(), first.utime);  // the mapper's publish time
  EXPECT_EQ(h["arrays"].size(), 3u);                          // positions, indices, colours

  f.publish(f.channels.mesh, update(1, {block(0, 0, 0, false), block(2, 0, 0)}));
  f.drain();
  EXPECT_EQ(meshIds(f.scene), (std::set<std::string>{"block:1,0,0", "block:2,0,0"}));
  EXPECT_EQ(f.scene.get("block:0,0,0"), nullptr);
  EXPECT_EQ(f.live.counters().mesh_updates_lost, 0u);

  // Update 2 lost; then a full update: every block not in it has no surface any more.
  f.publish(f.channels.mesh, update(3, {block(2, 0, 0)}));
  f.publish(f.channels.mesh, update(4, {block(5, 5, 5), block(2, 0, 0)}, true));
  f.drain();
  EXPECT_EQ(meshIds(f.scene), (std::set<std::string>{"block:2,0,0", "block:5,5,5"}));
  const view::LiveCounters c = f.live.counters();
  EXPECT_EQ(c.mesh_updates, 4u);
  EXPECT_EQ(c.mesh_updates_lost, 1u);
  EXPECT_EQ(c.blocks, 2u);
  EXPECT_EQ(c.bad_messages, 0u);
  EXPECT_EQ(f.header("stats")["values"]["mesh blocks"], 2);
}

TEST(ViewLive, TheCameraPoseCarriesTheIntrinsicsAndBothTrajectoriesGrow) {
  Fixture f;
  CameraIntrinsics k;
  k.width_px = 640;
  k.height_px = 480;
  k.fx_px = k.fy_px = 525.0f;
  k.cx_px = 319.5f;
  k.cy_px = 239.5f;
  f.publish(f.channels.camera_info, lcm_io::encodeCameraInfo(k, "depth", 1));
  for (int i = 0; i < 5; ++i) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.1 * i, 0.0, 1.5);
    f.publish(f.channels.pose, lcm_io::encodePose(T, 1000 + i));
  }
  // A frame with its pose inside (the images are not read).
  rgbd_frame_t frame{};
  frame.utime = 2000;
  frame.camera_id = "depth";
  frame.depth.encoding = "depth16";
  frame.depth.width = 2;
  frame.depth.height = 1;
  frame.depth.size = 4;
  frame.depth.data = {1, 2, 3, 4};
  frame.has_pose = true;
  Eigen::Isometry3d T_frame = Eigen::Isometry3d::Identity();
  T_frame.translation() = Eigen::Vector3d(2.0, 3.0, 1.0);
  frame.pose = lcm_io::encodePose(T_frame, 2000);
  const std::int64_t before_us = lcm_io::nowUtime();
  f.publish(f.channels.rgbd, frame);
  f.drain();

  const nlohmann::json pose = f.header("pose");
  ASSERT_EQ(pose["type"], "pose");
  EXPECT_EQ(pose["id"], "camera");
  EXPECT_EQ(pose["intrinsics"]["width"], 640.0);
  EXPECT_DOUBLE_EQ(pose["intrinsics"]["fx"].get<double>(), 525.0);
  EXPECT_DOUBLE_EQ(pose["T_W_C"][3].get<double>(), 2.0);  // row-major: x of the translation
  EXPECT_DOUBLE_EQ(pose["T_W_C"][7].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(pose["t"].get<double>(), 2000e-6);
  EXPECT_GE(pose["t_pub_us"].get<std::int64_t>(), before_us);       // received now
  EXPECT_EQ(f.header("trajectory:vio")["arrays"][0]["count"], 15);  // 5 points
  EXPECT_EQ(f.header("trajectory:map")["arrays"][0]["count"], 3);
  EXPECT_EQ(f.live.counters().poses, 6u);
  EXPECT_EQ(f.live.counters().bad_messages, 0u);
}

TEST(ViewLive, StatsCarryTheMapperBlockCountFramesSessionAndDeviceMemory) {
  Fixture f;
  map_stats_t s{};
  s.utime = lcm_io::nowUtime();
  s.frames_fused = 42;
  s.frames_received = 45;
  s.blocks = 1234;
  s.device_bytes = 5'000'000;
  s.session = 2;
  s.session_active = true;
  s.last_command_result = "ok";
  s.bad_channel = {"STRATA_RGBD"};
  s.bad_count = {3};
  s.num_channels = 1;
  f.publish(f.channels.stats, s);
  f.drain();
  const nlohmann::json v = f.header("stats")["values"];
  EXPECT_EQ(v["blocks"], 1234);
  EXPECT_EQ(v["frames"], 42);
  EXPECT_EQ(v["session"], 2);
  EXPECT_EQ(v["session open"], true);
  EXPECT_DOUBLE_EQ(v["device MB"].get<double>(), 5.0);
  EXPECT_EQ(v["view bad messages"], 0);
  EXPECT_EQ(f.header("hello")["mode"], "live");
}

TEST(ViewLive, ObjectsOfASessionEndAreReplacedByTheModelsMadeFromThem) {
  Fixture f;
  change_event_t e{};
  e.session = 1;
  e.object_id = 1;
  e.num_objects = 1;
  e.vertices = {{1.0f, 1.0f, 0.0f}, {1.2f, 1.0f, 0.0f}, {1.0f, 1.3f, 0.4f}};
  e.triangles = {{0, 1, 2}};
  e.num_vertices = 3;
  e.num_triangles = 1;
  f.publish(f.channels.change, e);
  f.drain();
  EXPECT_EQ(meshIds(f.scene), (std::set<std::string>{"object:1:1"}));
  EXPECT_EQ(f.header("object:1:1")["group"], "object");
  nlohmann::json objects = f.header("objects")["items"];
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_FLOAT_EQ(objects[0]["max"][1].get<float>(), 1.3f);

  object_update_t u{};
  u.session = 1;
  u.model_id = 7;
  u.new_model = true;
  object_instance_t instance{};
  instance.session = 1;
  instance.segment_id = 1;
  const double T[16] = {1, 0, 0, 1.0, 0, 1, 0, 1.0,
                        0, 0, 1, 0.0, 0, 0, 0, 1};  // model at (1, 1, 0)
  std::copy(T, T + 16, instance.T_W_M);
  u.instances = {instance};
  u.num_instances = 1;
  u.vertices = {{0.0f, 0.0f, 0.0f}, {0.2f, 0.0f, 0.0f}, {0.0f, 0.3f, 0.4f}};
  u.triangles = {{0, 1, 2}};
  u.num_vertices = 3;
  u.num_triangles = 1;
  f.publish(f.channels.objects, u);
  f.drain();
  EXPECT_EQ(meshIds(f.scene), (std::set<std::string>{"model:7"}));
  objects = f.header("objects")["items"];
  ASSERT_EQ(objects.size(), 1u);
  EXPECT_EQ(objects[0]["label"], "model 7");
  EXPECT_FLOAT_EQ(objects[0]["min"][0].get<float>(), 1.0f);  // placed by T_W_M
  EXPECT_FLOAT_EQ(objects[0]["max"][1].get<float>(), 1.3f);
}

TEST(ViewLive, QueriesAreAnsweredFromTheSliceAtItsHeightOnly) {
  Fixture f;
  EXPECT_EQ(query(f.live, 0.1f, 0.1f, 1.0f)["type"], "error");  // no slice yet
  f.publish(f.channels.esdf, slice());
  f.drain();
  const nlohmann::json drawn = f.header("esdf");
  ASSERT_EQ(drawn["type"], "esdf_slice");
  EXPECT_EQ(drawn["width"], 4);
  EXPECT_FLOAT_EQ(drawn["origin"][0].get<float>(), -0.05f);  // the corner, not the first centre

  nlohmann::json a = query(f.live, 0.1f, 0.2f, 1.0f);  // the centre of cell (r 2, c 1)
  ASSERT_EQ(a["type"], "answer");
  EXPECT_EQ(a["id"], 7);
  EXPECT_TRUE(a["known"].get<bool>());
  EXPECT_NEAR(a["distance"].get<float>(), 0.12f, 1e-5f);
  a = query(f.live, 0.15f, 0.05f, 1.04f);  // between four known cells, just inside the slice
  EXPECT_NEAR(a["distance"].get<float>(), 0.1f * 1.5f + 0.01f * 0.5f, 1e-5f);
  a = query(f.live, 0.3f, 0.2f, 1.0f);  // the unobserved cell
  EXPECT_FALSE(a["known"].get<bool>());
  a = query(f.live, 5.0f, 0.0f, 1.0f);  // off the slice
  EXPECT_FALSE(a["known"].get<bool>());

  a = query(f.live, 0.1f, 0.1f, 1.2f);
  ASSERT_EQ(a["type"], "error");
  EXPECT_NE(a["message"].get<std::string>().find("slice at z = 1.000 m"), std::string::npos)
      << a["message"];
  a = view::decodeMessage(*f.live.answer({{"type", "slice"}, {"z", 0.5}})).header;
  ASSERT_EQ(a["type"], "error");
  EXPECT_NE(a["message"].get<std::string>().find("mapper chooses"), std::string::npos);
  const nlohmann::json short_point = {{"type", "query"}, {"point", {1, 2}}};
  EXPECT_THROW(f.live.answer(short_point), InputError);
  const nlohmann::json unknown = {{"type", "teleport"}};
  EXPECT_THROW(f.live.answer(unknown), InputError);

  // An empty slice (no block at its height any more) takes it away.
  esdf_slice_t empty{};
  empty.resolution_m = 0.1f;
  f.publish(f.channels.esdf, empty);
  f.drain();
  EXPECT_EQ(f.scene.get("esdf"), nullptr);
  EXPECT_EQ(query(f.live, 0.1f, 0.2f, 1.0f)["type"], "error");
}

TEST(ViewLive, CorruptMessagesAreCountedAndSkipped) {
  Fixture f;
  f.publish(f.channels.mesh, update(0, {block(0, 0, 0)}));
  f.drain();
  const std::set<std::string> shown = meshIds(f.scene);

  std::vector<std::uint8_t> valid = encoded(update(1, {block(1, 1, 1)}));
  std::vector<std::uint8_t> huge_count = valid;
  // num_blocks (after hash, utime, last_frame_utime, sequence, full, voxel size) claims 2^31 - 1.
  const std::size_t num_blocks_at = 8 + 8 + 8 + 8 + 1 + 4;
  for (int i = 0; i < 4; ++i) huge_count[num_blocks_at + i] = i == 0 ? 0x7f : 0xff;
  mesh_update_t bad_index = update(1, {block(1, 1, 1)});
  bad_index.blocks[0].triangles[0][2] = 3;  // one past its vertices
  mesh_update_t nan_vertex = update(1, {block(1, 1, 1)});
  nan_vertex.blocks[0].vertices[1][0] = std::nanf("");
  esdf_slice_t huge_slice = slice();
  std::vector<std::uint8_t> slice_bytes = encoded(huge_slice);
  for (int i = 0; i < 4; ++i) slice_bytes[8 + 8 + 8 + 16 + i] = i == 0 ? 0x40 : 0;  // width 2^30
  pose_t not_world = lcm_io::encodePose(Eigen::Isometry3d::Identity(), 1, "odom");

  int bad = 0;
  f.publishBytes(f.channels.mesh, {1, 2, 3});  // too short
  f.publishBytes(f.channels.mesh, std::vector<std::uint8_t>(valid.begin(), valid.end() - 5));
  f.publishBytes(f.channels.mesh, huge_count);
  f.publish(f.channels.mesh, bad_index);
  f.publish(f.channels.mesh, nan_vertex);
  f.publishBytes(f.channels.mesh, encoded(slice()));  // another type
  f.publishBytes(f.channels.esdf, slice_bytes);
  f.publish(f.channels.pose, not_world);
  bad += 8;
  std::mt19937 random(5);
  for (const std::string* channel :
       {&f.channels.mesh, &f.channels.esdf, &f.channels.stats, &f.channels.change,
        &f.channels.objects, &f.channels.pose, &f.channels.rgbd, &f.channels.camera_info}) {
    std::vector<std::uint8_t> noise(64 + random() % 512);
    for (auto& b : noise) b = static_cast<std::uint8_t>(random());
    f.publishBytes(*channel, noise);
    ++bad;
  }
  f.drain();
  view::LiveCounters c = f.live.counters();
  EXPECT_EQ(c.bad_messages, static_cast<std::uint64_t>(bad)) << c.last_error;
  EXPECT_EQ(meshIds(f.scene), shown);
  EXPECT_EQ(c.mesh_updates, 1u);
  EXPECT_EQ(f.header("stats")["values"]["view bad messages"], bad);

  // Bit flips of valid messages: decoded or refused, never a crash; the valid one still applies.
  for (int i = 0; i < 2000; ++i) {
    std::vector<std::uint8_t> flipped = valid;
    flipped[random() % flipped.size()] ^= static_cast<std::uint8_t>(1u << (random() % 8));
    f.publishBytes(f.channels.mesh, flipped);
    if (i % 100 == 0) f.drain();
  }
  f.drain();
  f.publishBytes(f.channels.mesh, valid);
  f.drain();
  EXPECT_NE(f.scene.get("block:1,1,1"), nullptr);
}

TEST(ViewLive, ShowsTheBlocksAndBlockCountOfARealMapper) {
  constexpr int kFrames = 4;
  InProcessMapper mapper(testMapperOptions());
  view::Scene scene;
  // NOTE: the view's handlers run on the mapper's receive thread (memq:// is one LCM object).
  auto live = std::make_unique<LiveView>(mapper.lcm(), scene, view::LiveChannels{}, "test");
  apps::FramePublisher publisher(mapper.lcm(), apps::PublisherChannels::defaults(), "depth",
                                 lcm_io::FrameEncoding{});
  const auto session = roomSession(0, kFrames);
  for (std::size_t i = 0; i < session->size(); ++i) {
    publisher.publish(session->load(i), session->intrinsics(), lcm_io::nowUtime());
  }
  const auto framesShown = [&] {
    const view::Message m = scene.get("stats");
    return m ? view::decodeMessage(*m).header["values"].value("frames", 0) : 0;
  };
  ASSERT_TRUE(InProcessMapper::waitFor([&] { return framesShown() == kFrames; }));
  mapper.stop();  // nothing more is dispatched to the view

  const map_stats_t stats = mapper.outputs().latestStats();
  const nlohmann::json values = view::decodeMessage(*scene.get("stats")).header["values"];
  EXPECT_EQ(values["blocks"].get<std::int64_t>(), stats.blocks);
  EXPECT_GT(stats.blocks, 0);
  std::set<std::string> with_surface;
  {
    std::lock_guard<std::mutex> lock(mapper.outputs().mutex);
    for (const mesh_update_t& u : mapper.outputs().mesh_updates) {
      if (u.full) with_surface.clear();
      for (const mesh_block_t& b : u.blocks) {
        if (b.num_triangles > 0) {
          with_surface.insert(view::blockId(b.index));
        } else {
          with_surface.erase(view::blockId(b.index));
        }
      }
    }
  }
  EXPECT_FALSE(with_surface.empty());
  EXPECT_EQ(meshIds(scene), with_surface);
  EXPECT_EQ(live->counters().bad_messages, 0u);
  EXPECT_EQ(live->counters().poses, static_cast<std::uint64_t>(kFrames));  // poses in the frames
  EXPECT_NE(scene.get("pose"), nullptr);
}

}  // namespace
}  // namespace strata::test

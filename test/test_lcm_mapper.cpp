// strata-mapper in-process over memq://: the same voxels as `strata fuse`, complete mesh updates,
// backpressure that drops the oldest frames, commands, and change events when a session ends.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "cli/fuse_command.h"
#include "strata/core/atomic_file.h"
#include "strata/io/open_dataset.h"
#include "strata/io/tum_writer.h"
#include "strata/lcm/channels.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/lcm_time.h"
#include "lcm_test_helpers.h"
#include "strata/map/map_file.h"
#include "strata/mesh/extract_mesh.h"
#include "test_utils.h"

namespace strata::test {
namespace {

namespace fs = std::filesystem;

map_stats_t waitForFused(InProcessMapper& mapper, std::int64_t frames) {
  const bool done = InProcessMapper::waitFor([&] {
    const map_stats_t s = mapper.outputs().latestStats();
    return s.frames_fused + s.frames_dropped_backlog + s.frames_rejected >= frames;
  });
  EXPECT_TRUE(done) << "the mapper did not account for " << frames << " frames in time";
  return mapper.outputs().latestStats();
}

/// Sends a command and waits for the mapper's reply in its stats; returns the result.
std::string runCommand(InProcessMapper& mapper, apps::FramePublisher& publisher,
                       std::int8_t command, const std::string& argument = "") {
  const std::int64_t id = publisher.command(command, argument);
  std::string result = "(no reply)";
  InProcessMapper::waitFor([&] {
    const map_stats_t s = mapper.outputs().latestStats();
    if (s.last_command_id != id) return false;
    result = s.last_command_result;
    return true;
  });
  return result;
}

apps::FramePublisher publisherFor(InProcessMapper& mapper, const std::string& depth_encoding) {
  lcm_io::FrameEncoding encoding;
  encoding.depth = depth_encoding;
  return apps::FramePublisher(mapper.lcm(), apps::PublisherChannels::defaults(), "depth", encoding);
}

TEST(LcmMapper, FusesTheSameVoxelsAsStrataFuseAndItsMeshUpdatesAreComplete) {
  constexpr int kFrames = 20;
  const fs::path dir = freshTempDir("lcm_same_voxels");
  {
    const auto session = roomSession(0, kFrames);
    TumWriter writer((dir / "session").string(), session->intrinsics());
    for (std::size_t i = 0; i < session->size(); ++i) writer.add(session->load(i));
    writer.finish();
  }
  apps::FuseOptions fuse;
  fuse.dataset = (dir / "session").string();
  fuse.map.voxel_size_m = 0.05f;
  fuse.free_space = 1;
  fuse.map_path = (dir / "fuse.strata").string();
  fuse.quiet = true;
  ASSERT_EQ(apps::runFuse(fuse), 0);

  apps::MapperOptions options = testMapperOptions();
  options.map.voxel_size_m = 0.05f;
  InProcessMapper mapper(options);
  apps::FramePublisher publisher = publisherFor(mapper, "depth16");
  const auto dataset = openDataset((dir / "session").string());
  ASSERT_EQ(dataset->size(), static_cast<std::size_t>(kFrames));
  for (std::size_t i = 0; i < dataset->size(); ++i) {
    const RgbdFrame frame = dataset->load(i);
    publisher.publish(frame, dataset->intrinsics(), lcm_io::secondsToUtime(frame.timestamp_s));
  }
  const map_stats_t stats = waitForFused(mapper, kFrames);
  EXPECT_EQ(stats.frames_fused, kFrames);
  EXPECT_EQ(stats.messages_bad, 0);
  EXPECT_EQ(runCommand(mapper, publisher, command_t::SAVE_MAP, (dir / "lcm.strata").string()),
            "ok");
  ASSERT_TRUE(mapper.stop());

  // Identical voxels: the map files (deterministic serialisation) are byte for byte the same.
  EXPECT_TRUE(readFile((dir / "lcm.strata").string()) == readFile(fuse.map_path))
      << "the map fused over LCM differs from strata fuse's";
  const Mesh mesh = extractMesh(loadMap(fuse.map_path));
  EXPECT_GT(mesh.triangles.size(), 1000u);
  EXPECT_EQ(mapper.outputs().viewerTriangles(), mesh.triangles.size())
      << "a viewer applying every mesh update must hold the whole map's mesh";
  // Keyframe scores (scored before fusion, which they must not disturb: the voxels above match).
  std::lock_guard<std::mutex> lock(mapper.outputs().mutex);
  const std::vector<keyframe_score_t>& scores = mapper.outputs().keyframe_scores;
  ASSERT_EQ(scores.size(), static_cast<std::size_t>(kFrames));
  EXPECT_EQ(scores.front().coverage, 0.0f) << "nothing mapped before the first frame";
  EXPECT_TRUE(scores.front().selected);
  EXPECT_GT(scores.back().coverage, 0.5f) << "the map explains most of the last frame";
  fs::remove_all(dir);
}

TEST(LcmMapper, BackpressureDropsTheOldestFramesAndKeepsTheNewest) {
  constexpr int kFrames = 12;
  apps::MapperOptions options = testMapperOptions();
  options.queue_capacity = 2;
  InProcessMapper mapper(options);
  apps::FramePublisher publisher = publisherFor(mapper, "depth16");
  const auto session = roomSession(0, kFrames);
  std::vector<RgbdFrame> frames;
  for (std::size_t i = 0; i < session->size(); ++i) frames.push_back(session->load(i));
  const std::int64_t t0 = lcm_io::nowUtime();
  for (int i = 0; i < kFrames; ++i) {  // a burst: far faster than fusion
    publisher.publish(frames[i], session->intrinsics(), t0 + 33000 * i);
  }
  const map_stats_t stats = waitForFused(mapper, kFrames);
  EXPECT_EQ(stats.frames_received, kFrames);
  EXPECT_GE(stats.frames_dropped_backlog, 1);
  EXPECT_EQ(stats.frames_fused + stats.frames_dropped_backlog, kFrames);
  EXPECT_EQ(stats.last_frame_utime, t0 + 33000 * (kFrames - 1)) << "the newest frame is fused";
  std::lock_guard<std::mutex> lock(mapper.outputs().mutex);
  for (const map_stats_t& s : mapper.outputs().stats) {
    EXPECT_LE(s.queue_depth, 2) << "the queue never grows beyond its capacity";
  }
}

TEST(LcmMapper, SavesTheMapOnItsTimerWhileFusing) {
  constexpr int kFrames = 4;
  const fs::path dir = freshTempDir("lcm_timed_save");
  apps::MapperOptions options = testMapperOptions();
  options.map_path = (dir / "timed.strata").string();
  options.save_every_s = 0.05;
  InProcessMapper mapper(options);
  apps::FramePublisher publisher = publisherFor(mapper, "depth16");
  const auto session = roomSession(0, kFrames);
  const std::int64_t t0 = lcm_io::nowUtime();
  for (int i = 0; i < kFrames; ++i) {
    publisher.publish(session->load(i), session->intrinsics(), t0 + 33000 * i);
    waitForFused(mapper, i + 1);
    // A save is due once the interval has passed and a frame was fused since the last one.
    std::this_thread::sleep_for(std::chrono::milliseconds(80));
  }
  EXPECT_TRUE(InProcessMapper::waitFor([&] { return fs::exists(options.map_path); }, 30.0))
      << "no timed save while the node ran (it was not stopped yet)";
  const TsdfMap saved = loadMap(options.map_path);
  EXPECT_GT(saved.blockCount(), 0u);
  mapper.stop();
  fs::remove_all(dir);
}

TEST(LcmMapper, CommandsSaveRequestTheMeshAndReportFailuresWithoutStopping) {
  const fs::path dir = freshTempDir("lcm_commands");
  InProcessMapper mapper(testMapperOptions());
  apps::FramePublisher publisher = publisherFor(mapper, "depth32f");
  EXPECT_EQ(runCommand(mapper, publisher, command_t::STOP_SESSION), "error: no session is open");
  const auto session = roomSession(1, 3);
  const std::int64_t t0 = lcm_io::nowUtime();
  for (std::size_t i = 0; i < session->size(); ++i) {
    publisher.publish(session->load(i), session->intrinsics(), t0 + 100000 * i);
  }
  waitForFused(mapper, 3);
  const std::string bad_path = (dir / "missing_folder" / "map.strata").string();
  EXPECT_EQ(runCommand(mapper, publisher, command_t::SAVE_MAP, bad_path).rfind("error: ", 0), 0u);
  EXPECT_EQ(runCommand(mapper, publisher, command_t::REQUEST_MESH), "ok");
  EXPECT_EQ(runCommand(mapper, publisher, command_t::SAVE_MAP, (dir / "m.strata").string()), "ok");
  EXPECT_EQ(runCommand(mapper, publisher, command_t::STOP_SESSION), "ok");
  mapper.stop();
  const TsdfMap saved = loadMap((dir / "m.strata").string());
  std::lock_guard<std::mutex> lock(mapper.outputs().mutex);
  const auto full =
      std::find_if(mapper.outputs().mesh_updates.begin(), mapper.outputs().mesh_updates.end(),
                   [](const mesh_update_t& u) { return u.full; });
  ASSERT_NE(full, mapper.outputs().mesh_updates.end());
  std::size_t triangles = 0;
  for (const mesh_block_t& block : full->blocks) triangles += block.num_triangles;
  EXPECT_EQ(triangles, extractMesh(saved).triangles.size());
  fs::remove_all(dir);
}

TEST(LcmMapper, PosesFromThePoseChannelAreLookedUpByTimestamp) {
  InProcessMapper mapper(testMapperOptions());
  lcm_io::FrameEncoding encoding;
  encoding.with_pose = false;  // FramePublisher then sends each pose on STRATA_POSE first
  apps::FramePublisher publisher(mapper.lcm(), apps::PublisherChannels::defaults(), "depth",
                                 encoding);
  const auto session = roomSession(2, 4);
  const std::int64_t t0 = lcm_io::nowUtime();
  for (std::size_t i = 0; i < session->size(); ++i) {
    publisher.publish(session->load(i), session->intrinsics(), t0 + 100000 * i);
  }
  // A frame between two poses is interpolated.
  rgbd_frame_t between =
      lcm_io::encodeFrame(session->load(0), t0 + 100000 * 4, "depth", 9, encoding);
  const pose_t pose_5 = lcm_io::encodePose(session->load(0).T_W_C, t0 + 100000 * 5);
  mapper.lcm().publish(lcm_io::kPoseChannel, &pose_5);
  mapper.lcm().publish(lcm_io::kRgbdChannel, &between);
  const map_stats_t stats = waitForFused(mapper, 5);
  EXPECT_EQ(stats.frames_fused, 5);
  EXPECT_EQ(stats.frames_dropped_no_pose, 0);
  // A frame newer than every pose waits for the next one; poses 2 s apart are too far apart to
  // interpolate between: it is dropped and counted, not guessed.
  rgbd_frame_t waiting = between;
  waiting.utime = t0 + 100000 * 5 + 10;
  mapper.lcm().publish(lcm_io::kRgbdChannel, &waiting);
  const pose_t pose_far = lcm_io::encodePose(session->load(0).T_W_C, t0 + 100000 * 5 + 2000000);
  mapper.lcm().publish(lcm_io::kPoseChannel, &pose_far);
  InProcessMapper::waitFor(
      [&] { return mapper.outputs().latestStats().frames_dropped_no_pose == 1; });
  EXPECT_EQ(mapper.outputs().latestStats().frames_dropped_no_pose, 1);
  EXPECT_EQ(mapper.outputs().latestStats().frames_fused, 5);
}

}  // namespace
}  // namespace strata::test

// strata-mapper's sessions over LCM: ending a session publishes the objects that changed since
// the earlier sessions as change events, with their meshes, and the object database's models
// they created or extended (object_update_t), and writes the database file.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>

#include "strata/core/error.h"
#include "fusion_fixture.h"
#include "strata/lcm/lcm_time.h"
#include "lcm_test_helpers.h"
#include "strata/objects/object_database.h"
#include "strata/objects/object_database_file.h"
#include "test_utils.h"

namespace strata::test {
namespace {

std::string runCommand(InProcessMapper& mapper, apps::FramePublisher& publisher,
                       std::int8_t command) {
  const std::int64_t id = publisher.command(command);
  std::string result = "(no reply)";
  InProcessMapper::waitFor([&] {
    const map_stats_t s = mapper.outputs().latestStats();
    if (s.last_command_id != id) return false;
    result = s.last_command_result;
    return true;
  });
  return result;
}

void sendSession(apps::FramePublisher& publisher, int session, int frames, std::int64_t* utime) {
  const auto data = roomSession(session, frames);
  for (std::size_t i = 0; i < data->size(); ++i) {
    publisher.publish(data->load(i), data->intrinsics(), *utime += 100000);
  }
}

/// The object database's messages of session `session`: one per model it touched, numbered, each
/// with a mesh and an instance in that session taken from one of the session's change events.
void expectObjectUpdates(const std::vector<object_update_t>& updates,
                         const std::vector<change_event_t>& events, int session) {
  ASSERT_FALSE(updates.empty()) << "the session's objects join the database";
  std::set<int> models;
  std::set<int> segments;
  for (const object_update_t& u : updates) {
    EXPECT_EQ(u.session, session);
    EXPECT_EQ(u.num_updates, static_cast<int>(updates.size()));
    EXPECT_TRUE(models.insert(u.model_id).second) << "one message per model";
    EXPECT_GT(u.num_triangles, 0) << "model " << u.model_id;
    EXPECT_EQ(u.num_vertices, static_cast<int>(u.vertices.size()));
    EXPECT_GT(u.surface_area_m2, 0.0f);
    bool in_session = false;
    for (const object_instance_t& instance : u.instances) {
      if (instance.session != session) continue;
      in_session = true;
      segments.insert(instance.segment_id);
      EXPECT_DOUBLE_EQ(instance.T_W_M[15], 1.0);
      EXPECT_GT(instance.match_score, 0.0f);
    }
    EXPECT_TRUE(in_session) << "model " << u.model_id << " has no instance in the session";
  }
  for (const int segment : segments) {
    EXPECT_TRUE(std::any_of(events.begin(), events.end(),
                            [&](const change_event_t& e) { return e.object_id == segment; }))
        << "instance of segment " << segment << " without its change event";
  }
}

TEST(LcmMapperSessions, EndingASessionPublishesItsChangedObjects) {
  constexpr int kFrames = 15;
  apps::MapperOptions options = testMapperOptions();
  options.change_detection = true;
  options.mesh_rate_hz = 1.0;
  const std::filesystem::path dir = freshTempDir("lcm_objects");
  const std::string objects_file = (dir / "room.objects").string();
  options.objects_path = objects_file;
  InProcessMapper mapper(options);
  apps::FramePublisher publisher(mapper.lcm(), apps::PublisherChannels::defaults(), "depth",
                                 lcm_io::FrameEncoding{});
  std::int64_t utime = lcm_io::nowUtime();
  sendSession(publisher, 0, kFrames, &utime);
  EXPECT_EQ(runCommand(mapper, publisher, command_t::STOP_SESSION), "ok");
  {
    std::lock_guard<std::mutex> lock(mapper.outputs().mutex);
    EXPECT_TRUE(mapper.outputs().change_events.empty()) << "the first session is the reference";
    EXPECT_TRUE(mapper.outputs().object_updates.empty()) << "no object, no model";
  }
  EXPECT_EQ(runCommand(mapper, publisher, command_t::START_SESSION), "ok");
  sendSession(publisher, 1, kFrames, &utime);
  EXPECT_EQ(runCommand(mapper, publisher, command_t::STOP_SESSION), "ok");
  const map_stats_t stats = mapper.outputs().latestStats();
  EXPECT_EQ(stats.frames_fused, 2 * kFrames);
  EXPECT_EQ(stats.session, 1);
  EXPECT_FALSE(stats.session_active);

  // The database is updated on a thread of its own after the session end: its updates follow.
  EXPECT_TRUE(InProcessMapper::waitFor([&] {
    std::lock_guard<std::mutex> lock(mapper.outputs().mutex);
    return !mapper.outputs().object_updates.empty();
  })) << "no object update within a minute of the session end";
  ASSERT_TRUE(mapper.stop());  // the worker is done: its core may be read from here
  std::lock_guard<std::mutex> lock(mapper.outputs().mutex);
  expectObjectUpdates(mapper.outputs().object_updates, mapper.outputs().change_events, 1);
  const objects::ObjectDatabase* database = mapper.core().objectDatabase();
  ASSERT_NE(database, nullptr);
  const objects::ObjectDatabase saved = objects::loadObjectDatabase(objects_file);
  EXPECT_EQ(saved.models().size(), database->models().size())
      << "the database file is written at every session end";
  const std::vector<change_event_t>& events = mapper.outputs().change_events;
  ASSERT_FALSE(events.empty()) << "the room's session 1 moves objects";
  for (const change_event_t& e : events) {
    EXPECT_EQ(e.session, 1);
    EXPECT_EQ(e.num_objects, static_cast<int>(events.size()));
    EXPECT_GT(e.num_triangles, 0);
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(e.bbox_min[a], e.centroid[a]);
      EXPECT_GE(e.bbox_max[a], e.centroid[a]);
    }
  }
}

TEST(LcmMapperSessions, ACorruptObjectDatabaseIsRefusedAndLeftUntouched) {
  const std::filesystem::path dir = freshTempDir("lcm_objects_bad");
  const std::string path = (dir / "map.objects").string();
  const std::string garbage = "not an object database";
  {
    std::ofstream out(path, std::ios::binary);
    out << garbage;
  }
  apps::MapperOptions options = testMapperOptions();
  options.change_detection = true;
  options.objects_path = path;
  try {
    apps::MapperCore core(sharedContext(), options);
    ADD_FAILURE() << "a corrupt database must stop the mapper from starting";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("object database"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  std::ifstream in(path, std::ios::binary);
  const std::string kept((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(kept, garbage) << "the file someone may still recover is left as it was";
  options.objects_path.clear();
  options.map_path = (dir / "map.strata").string();
  EXPECT_EQ(options.objectsFile(), path) << "beside the map by default";
  options.object_database = false;
  EXPECT_NO_THROW(apps::MapperCore(sharedContext(), options)) << "--no-objects ignores the file";
}

}  // namespace
}  // namespace strata::test

// strata-mapper's sessions over LCM: ending a session publishes the objects that changed since
// the earlier sessions as change events, with their meshes.
#include <gtest/gtest.h>

#include "lcm/lcm_time.h"
#include "lcm_test_helpers.h"

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

TEST(LcmMapperSessions, EndingASessionPublishesItsChangedObjects) {
  constexpr int kFrames = 15;
  apps::MapperOptions options = testMapperOptions();
  options.change_detection = true;
  options.mesh_rate_hz = 1.0;
  InProcessMapper mapper(options);
  apps::FramePublisher publisher(mapper.lcm(), apps::PublisherChannels::defaults(), "depth",
                                 lcm_io::FrameEncoding{});
  std::int64_t utime = lcm_io::nowUtime();
  sendSession(publisher, 0, kFrames, &utime);
  EXPECT_EQ(runCommand(mapper, publisher, command_t::STOP_SESSION), "ok");
  {
    std::lock_guard<std::mutex> lock(mapper.outputs().mutex);
    EXPECT_TRUE(mapper.outputs().change_events.empty()) << "the first session is the reference";
  }
  EXPECT_EQ(runCommand(mapper, publisher, command_t::START_SESSION), "ok");
  sendSession(publisher, 1, kFrames, &utime);
  EXPECT_EQ(runCommand(mapper, publisher, command_t::STOP_SESSION), "ok");
  const map_stats_t stats = mapper.outputs().latestStats();
  EXPECT_EQ(stats.frames_fused, 2 * kFrames);
  EXPECT_EQ(stats.session, 1);
  EXPECT_FALSE(stats.session_active);

  std::lock_guard<std::mutex> lock(mapper.outputs().mutex);
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

}  // namespace
}  // namespace strata::test

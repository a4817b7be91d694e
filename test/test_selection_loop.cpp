// The keyframe-selection loop on the Mapper with plain datasets (no simulator truth): the first
// session is fused whole and sets the thresholds; a later session of the same scene selects
// nothing, one with a new box selects the frames that see it and fuses those; the observer
// sees every frame once, in order; the complete loop fuses everything.
#include <gtest/gtest.h>

#include <algorithm>

#include "change_pipeline_helpers.h"
#include "strata/core/error.h"
#include "fusion_fixture.h"
#include "strata/mapper/selection_loop.h"

namespace strata::selection {
namespace {

constexpr int kFrames = 6;

sim::Box newBox() {
  sim::Box box;
  box.centre_W = Eigen::Vector3d(-1.0, -0.3, 0.15);
  box.half_extents_m = Eigen::Vector3d(0.15, 0.15, 0.15);
  return box;
}

LoopConfig loopConfig(bool incremental) {
  LoopConfig c;
  c.map = test::testMapConfig(0.05f, true);
  c.selection.smoothing_window = 1;
  c.selection.dilation = 0;
  // The surface threshold is not set from the first session: the analytic scene's own frames
  // reach 0.03 against their 5 cm map (the default 0.02 suits real sensors' finer detail).
  c.selection.thresholds.surface_change = 0.05;
  c.incremental = incremental;
  return c;
}

/// Counts what a loop shows its observer.
struct CountingObserver : LoopObserver {
  bool wantsMapBefore() const override { return true; }
  void sessionStarted(int session, const TsdfMap& map_before) override {
    sessions.push_back(session);
    blocks_before.push_back(map_before.blockCount());
    next = 0;
  }
  void frameLoaded(std::size_t index, const RgbdFrame&) override {
    in_order = in_order && index == next;
    ++next;
  }
  void sessionEnded(const SessionRun& run) override { ended.push_back(run.session); }
  std::vector<int> sessions, ended;
  std::vector<std::size_t> blocks_before;
  std::size_t next = 0;
  bool in_order = true;
};

TEST(SelectionLoop, SelectsOnlyFramesThatSeeAChangeAndFusesThose) {
  const sim::AnalyticDataset before = test::analyticSession({}, kFrames);
  const sim::AnalyticDataset same = test::analyticSession({}, kFrames);
  const sim::AnalyticDataset changed = test::analyticSession({newBox()}, kFrames);
  SelectionLoop loop(test::sharedContext(), loopConfig(true));
  CountingObserver observer;
  const SessionRun first = loop.addSession(before, &observer);
  EXPECT_EQ(first.fusedCount(), static_cast<std::size_t>(kFrames)) << "the first session whole";
  EXPECT_EQ(first.scores.size(), static_cast<std::size_t>(kFrames)) << "scored for thresholds";
  const std::uint32_t blocks = loop.mapper().blockCount();

  const SessionRun repeat = loop.addSession(same, &observer);
  EXPECT_EQ(repeat.fusedCount(), 0u) << "the map already explains every frame";
  EXPECT_EQ(loop.mapper().blockCount(), blocks);

  const SessionRun& moved = loop.addSession(changed, &observer);
  EXPECT_GE(moved.fusedCount(), 1u) << "frames that see the new box";
  double most_repeat = 0.0, most_moved = 0.0;
  for (const auto& k : repeat.scores) most_repeat = std::max(most_repeat, k.depth_change_m);
  for (const auto& k : moved.scores) most_moved = std::max(most_moved, k.depth_change_m);
  EXPECT_GT(most_moved, 2.0 * most_repeat) << "the box changes the measured depth";
  EXPECT_EQ(moved.fused, moved.selection.selected);
  EXPECT_EQ(loop.mapper().framesIntegrated(), kFrames + moved.fusedCount());

  EXPECT_EQ(observer.sessions, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(observer.ended, (std::vector<int>{0, 1, 2}));
  EXPECT_TRUE(observer.in_order);
  EXPECT_EQ(observer.blocks_before.front(), 0u);
  EXPECT_EQ(observer.blocks_before.back(), blocks) << "the map before the changed session";

  SelectionLoop complete(test::sharedContext(), loopConfig(false));
  complete.addSession(before);
  EXPECT_EQ(complete.addSession(changed).fusedCount(), static_cast<std::size_t>(kFrames));
}

TEST(SelectionLoop, RefusesABadConfig) {
  LoopConfig c = loopConfig(true);
  c.selection.smoothing_window = 2;
  EXPECT_THROW(SelectionLoop(test::sharedContext(), c), InputError);
  c = loopConfig(true);
  c.changed_views.depth_tolerance_m = -1.0f;
  EXPECT_THROW(SelectionLoop(test::sharedContext(), c), InputError);
}

}  // namespace
}  // namespace strata::selection

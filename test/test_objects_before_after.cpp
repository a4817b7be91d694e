// The before / after picture of `strata objects --before-after` on the analytic L seen partially
// in three sessions: one column per merged model, the merged model showing more surface than its
// largest single view; a database without a merged model gives the notice instead.
#include <gtest/gtest.h>

#include "cli/objects_before_after.h"
#include "object_test_scene.h"

namespace strata::apps {
namespace {

constexpr int kSizePx = 120;
constexpr int kGapPx = 4, kLabelPx = 22;  // as objects_before_after.cpp lays the tiles out

struct Sessions {
  DiffResult result;
  std::vector<TsdfMap> maps;
};

Sessions sessionsOf(const std::vector<std::vector<test::Thing>>& sessions) {
  Sessions run;
  for (std::size_t i = 0; i < sessions.size(); ++i) {
    test::Session s = test::makeSession(sessions[i], static_cast<int>(i));
    DiffSession d;
    d.surface = std::move(s.surface);
    d.objects = std::move(s.segments);
    run.result.sessions.push_back(std::move(d));
    run.maps.push_back(std::move(s.map));
  }
  return run;
}

/// Pixels of a tile that differ from its top-left corner (the background: a miss).
int surfacePixels(const ColorImage& sheet, int x0, int y0) {
  const auto at = [&](int x, int y) {
    const std::size_t i = (static_cast<std::size_t>(y) * sheet.width_px + x) * 3;
    return std::array<std::uint8_t, 3>{sheet.rgb[i], sheet.rgb[i + 1], sheet.rgb[i + 2]};
  };
  int count = 0;
  for (int y = y0; y < y0 + kSizePx; ++y) {
    for (int x = x0; x < x0 + kSizePx; ++x) count += at(x, y) != at(x0, y0) ? 1 : 0;
  }
  return count;
}

TEST(ObjectsBeforeAfter, MergedModelShowsMoreThanItsLargestView) {
  const Sessions run = sessionsOf({{test::kL1}, {test::kL2, test::kBox}, {test::kL3}});
  const ObjectsRun objects = buildObjectDatabase(run.result, run.maps);
  int merged = 0;
  for (const auto& m : objects.database.models()) merged += m.merged_observations > 1 ? 1 : 0;
  ASSERT_GE(merged, 1) << "the L should be merged from several sessions";
  const ColorImage sheet = renderBeforeAfter(objects, run.result, run.maps, 4, kSizePx);
  EXPECT_EQ(sheet.width_px, merged * (kSizePx + kGapPx) + kGapPx);
  EXPECT_EQ(sheet.height_px, 2 * (kSizePx + kLabelPx + kGapPx) + kGapPx);
  const int before = surfacePixels(sheet, kGapPx, kGapPx + kLabelPx);
  const int after = surfacePixels(sheet, kGapPx, kGapPx + kSizePx + kLabelPx + kGapPx + kLabelPx);
  std::printf("first column: %d surface pixels before, %d after\n", before, after);
  EXPECT_GT(before, 200) << "the largest view should be visible";
  EXPECT_GT(after, before) << "merging should add surface the largest view lacks";
}

TEST(ObjectsBeforeAfter, NoMergedModelGivesTheNotice) {
  const Sessions run = sessionsOf({{test::kBox}});
  const ObjectsRun objects = buildObjectDatabase(run.result, run.maps);
  const ColorImage sheet = renderBeforeAfter(objects, run.result, run.maps, 4, kSizePx);
  EXPECT_EQ(sheet.width_px, 360);
  EXPECT_EQ(sheet.height_px, 40);
}

}  // namespace
}  // namespace strata::apps

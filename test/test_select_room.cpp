// Keyframe selection on the default multi-session room: the method against the NCC and
// histogram baselines on ground truth from the simulator (selection_truth.h), device against the
// host reference, and the incremental map (selected keyframes only) against the complete one.
// Room at 60 keyframes per session (the demo's default), 5 cm voxels to keep the suite quick.
// NOTE: one test case runs both loops (~1 min): ctest runs every case in its own process, so
// splitting the checks into cases would repeat the loops.
#include <gtest/gtest.h>

#include <cstdio>
#include <memory>

#include "fusion_fixture.h"
#include "strata/select/eval/selection_report.h"
#include "strata/sim/world/world_paths.h"

namespace strata::selection {
namespace {

constexpr int kFramesPerSession = 60;

std::vector<std::shared_ptr<sim::SimSessionDataset>> roomSessions() {
  const auto world = std::make_shared<const sim::World>(sim::World::load(sim::defaultWorldPath()));
  sim::SimSessionConfig config;
  config.max_frames = kFramesPerSession;
  std::vector<std::shared_ptr<sim::SimSessionDataset>> out;
  for (int s = 0; s < world->sessionCount(); ++s) {
    out.push_back(std::make_shared<sim::SimSessionDataset>(world, s, config));
  }
  return out;
}

void checkMethods(const SelectionLoop& complete, const LoopTruth& truth) {
  const std::vector<MethodResult> results = evaluateMethods(complete, truth);
  const Thresholds& t = complete.thresholds();
  std::printf(
      "automatic thresholds: coverage %.3f, colour change %.3f, depth change %.3f m, ncc %.3f, "
      "hist %.3f\n%s",
      t.coverage, t.color_change, t.depth_change_m, t.ncc, t.histogram,
      formatMethodTable(results).c_str());
  const Confusion& ours = results[0].confusion;
  const int positives = ours.true_positive + ours.false_negative;
  std::printf("truth: %d of %d keyframes of sessions 1-4 worth reconstructing\n", positives,
              ours.total());
  ASSERT_EQ(ours.total(), 4 * kFramesPerSession);
  EXPECT_GT(positives, 10) << "the room must have keyframes worth reconstructing";
  EXPECT_GE(ours.recall(), 0.85);
  EXPECT_GE(ours.precision(), 0.90);
  for (int baseline : {1, 2}) {
    const Confusion& other = results[baseline].confusion;
    EXPECT_GT(ours.recall(), other.recall()) << methodName(results[baseline].method);
    EXPECT_GT(ours.accuracy(), other.accuracy()) << methodName(results[baseline].method);
  }
}

void checkDeviceAgainstReference(const SelectionLoop& complete) {
  const DeviceReferenceAgreement a = deviceReferenceAgreement(complete);
  std::printf(
      "device vs reference: hit masks agree on %.4f %% of %zu samples, surface checks on "
      "%.4f %%; %zu of %zu x 3 decisions differ\n",
      100.0 * a.hitAgreement(), a.samples, 100.0 * a.surfaceAgreement(), a.decision_mismatches,
      a.keyframes);
  EXPECT_GE(a.hitAgreement(), 0.999);
  EXPECT_GE(a.surfaceAgreement(), 0.999);
  EXPECT_EQ(a.decision_mismatches, 0u);
}

/// Fused keyframes after the first session.
ImageUse printImageUse(const SelectionLoop& incremental) {
  const ImageUse use = imagesAfterFirstSession(incremental);
  std::printf("incremental: fused %zu of %zu keyframes after the first session (%.1f %%)\n",
              use.fused, use.total, 100.0 * use.share());
  return use;
}

TEST(SelectRoom, BeatsBaselinesAgreesWithReferenceAndKeepsCoverage) {
  SelectionLoop complete(test::sharedContext(), demoLoopConfig(false));
  SelectionLoop incremental(test::sharedContext(), demoLoopConfig(true));
  LoopTruth complete_truth, incremental_truth;
  for (const auto& session : roomSessions()) {
    complete_truth.addSession(complete, *session);
    incremental_truth.addSession(incremental, *session);
  }
  checkMethods(complete, complete_truth);
  checkDeviceAgainstReference(complete);
  printImageUse(incremental);
  const double complete_coverage = complete_truth.mapCoverage(complete).ratio();
  const double incremental_coverage = incremental_truth.mapCoverage(incremental).ratio();
  std::printf("surface coverage: incremental %.2f %%, complete %.2f %% (%.2f %% of it)\n",
              100.0 * incremental_coverage, 100.0 * complete_coverage,
              100.0 * incremental_coverage / complete_coverage);
  EXPECT_GE(incremental_coverage, 0.98 * complete_coverage);
}

}  // namespace
}  // namespace strata::selection

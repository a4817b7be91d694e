// Change-detection pipeline (steps 2-5): device against the C++ reference on a simulated
// room and for every kernel size; with noise-free aligned sessions S is the voxel-wise max;
// partial overlap; an uncovered floor entering S; misuse of the API. Layers: test_change_layers.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "change_pipeline_helpers.h"
#include "fusion_fixture.h"
#include "strata/change/change_device.h"
#include "strata/change/change_reference.h"
#include "strata/integrate/device_fusion.h"
#include "strata/sim/session/sim_session.h"

namespace strata {
namespace {

using change::ChangeDetector;
using change::LabelMap;
using change::VoxelLabel;

constexpr double kMinLabelAgreement = 0.999;  // target: device and reference labels

/// Device labels, dynamic parts and S against the reference fed with the device's session maps.
void expectDeviceMatchesReference(ChangeDetector& device, ChangeDetector& reference, int session) {
  const double d = change::labelAgreement(device.labels(), reference.labels());
  EXPECT_GE(d, kMinLabelAgreement) << "D after session " << session;
  for (int i = 0; i <= session; ++i) {
    const double p = change::labelAgreement(device.sessionDynamic(i), reference.sessionDynamic(i));
    EXPECT_GE(p, kMinLabelAgreement) << "dynamic part of session " << i << " after " << session;
  }
  const float min_weight = device.config().min_weight;
  const test::ValueComparison s =
      test::compareValues(device.staticMap(), reference.staticMap(), 1e-4f, min_weight);
  EXPECT_LE(s.share(), 1.0 - kMinLabelAgreement) << "S after session " << session;
  EXPECT_LE(double(s.observedness_mismatches), 1e-3 * double(s.compared));
  std::printf("[ change ] session %d: D agreement %.5f, S over 0.1 mm %zu of %zu\n", session, d,
              s.over_tolerance, s.compared);
}

TEST(ChangePipeline, DeviceMatchesReferenceOnSimulatedRoom) {
  const auto world = test::roomWorld();
  sim::SimSessionConfig session_config;
  session_config.max_frames = 15;  // noise on (the camera's default)
  const MapConfig map = test::testMapConfig(0.05f, true);
  const change::ChangeConfig config = test::testChangeConfig(0.05f);
  ChangeDetector device(test::sharedContext(), map, config);
  ChangeDetector reference(map, config);
  std::uint64_t dynamic_seen = 0;
  for (int s = 0; s < 3; ++s) {
    const sim::SimSessionDataset data(world, s, session_config);
    ASSERT_EQ(device.beginSession(), s);
    test::fuseSession(device, s, data, data.size());
    const change::ChangeUpdateStats stats = device.endSession(s);
    ASSERT_EQ(reference.addSessionMap(device.sessionMap(s)), s);
    const change::ChangeUpdateStats ref = reference.endSession(s);
    std::printf(
        "[ change ] session %d: %u blocks, device %.1f ms (reference %.0f ms), dynamic %llu"
        " (reference %llu)\n",
        s, stats.blocks, stats.stages.total(), ref.stages.total(),
        (unsigned long long)stats.dynamic_voxels, (unsigned long long)ref.dynamic_voxels);
    const change::ChangeStageTimes& t = stats.stages;
    std::printf("[ change ]   nb %.1f diff %.1f erode %.1f dilate %.1f static %.1f parts %.1f\n",
                t.neighbours_ms, t.difference_ms, t.erosion_ms, t.dilation_ms, t.static_update_ms,
                t.session_dynamic_ms);
    expectDeviceMatchesReference(device, reference, s);
    EXPECT_EQ(stats.session_dynamic_voxels, ref.session_dynamic_voxels);
    dynamic_seen += stats.dynamic_voxels;
  }
  EXPECT_GT(dynamic_seen, 100u) << "objects moved between the room's sessions";
}

sim::Box floorBox(double x, double y, double half_m) {
  sim::Box box;  // free spots on the floor of the default scene, seen from the whole arc
  box.centre_W = Eigen::Vector3d(x, y, half_m);
  box.half_extents_m = Eigen::Vector3d(half_m, half_m, half_m);
  return box;
}

/// Sessions fused from `datasets` on the device and ended in order; also fed to a reference.
void runSessions(ChangeDetector& device, ChangeDetector& reference,
                 const std::vector<const sim::AnalyticDataset*>& datasets) {
  for (const sim::AnalyticDataset* data : datasets) {
    const int s = device.beginSession();
    test::fuseSession(device, s, *data, data->size());
    device.endSession(s);
    reference.addSessionMap(device.sessionMap(s));
    reference.endSession(s);
  }
}

TEST(ChangePipeline, NoiseFreeAlignedSessionsGiveTheVoxelwiseMax) {
  constexpr float kVoxel = 0.04f;
  constexpr int kFrames = 10;
  // The same camera path each session; boxes come, go and move.
  const sim::AnalyticDataset a = test::analyticSession({floorBox(-1.0, -0.3, 0.15)}, kFrames);
  const sim::AnalyticDataset b =
      test::analyticSession({floorBox(-0.2, -0.8, 0.12), floorBox(-1.2, 0.9, 0.2)}, kFrames);
  const sim::AnalyticDataset c = test::analyticSession({}, kFrames);
  const MapConfig map = test::testMapConfig(kVoxel, false);
  const change::ChangeConfig config = test::testChangeConfig(kVoxel);
  ChangeDetector device(test::sharedContext(), map, config);
  ChangeDetector reference(map, config);
  runSessions(device, reference, {&a, &b, &c});
  std::vector<TsdfMap> sessions;
  for (int s = 0; s < 3; ++s) sessions.push_back(device.sessionMap(s));
  const TsdfMap expected = test::observedMax(sessions, config.min_weight);
  for (ChangeDetector* detector : {&device, &reference}) {
    // Close values are averaged (off by at most merge_close / 2); the rest must be the max.
    const test::ValueComparison c = test::compareValues(
        detector->staticMap(), expected, 0.5f * config.merge_close_m + 1e-4f, config.min_weight);
    std::printf("[ change ] %s S vs voxel-wise max: %zu of %zu over tolerance\n",
                detector->referenceMode() ? "reference" : "device", c.over_tolerance, c.compared);
    EXPECT_EQ(c.observedness_mismatches, 0u) << "S is observed exactly where a session was";
    EXPECT_LE(c.share(), 0.005);
  }
}

TEST(ChangePipeline, UncoveredFloorEntersStaticMapAndBelongsToNoSession) {
  constexpr float kVoxel = 0.04f;
  const sim::Box box = floorBox(-1.0, -0.3, 0.15);
  const sim::AnalyticDataset with_box = test::analyticSession({box}, 10);
  const sim::AnalyticDataset without = test::analyticSession({}, 10);
  const MapConfig map = test::testMapConfig(kVoxel, false);
  const change::ChangeConfig config = test::testChangeConfig(kVoxel);
  ChangeDetector device(test::sharedContext(), map, config);
  ChangeDetector reference(map, config);
  // The box stands in sessions 0 and 2 and is gone in session 1.
  runSessions(device, reference, {&with_box, &without, &with_box});
  // A dynamic part is the shell where the session's distance is clearly below S: it reaches
  // truncation - theta in front of the object (plus a voxel for the grid).
  const float reach = map.truncationDistance() - config.difference_threshold_m + kVoxel;
  for (ChangeDetector* detector : {&device, &reference}) {
    const std::string what = detector->referenceMode() ? "reference" : "device";
    const TsdfMap s = detector->staticMap();
    test::expectFloorUnder(s, box, config.min_weight, what);
    const std::size_t on_box_0 = test::dynamicNear(detector->sessionDynamic(0), box, reach);
    const std::size_t on_box_1 = test::dynamicNear(detector->sessionDynamic(1), box, reach);
    const std::size_t on_box_2 = test::dynamicNear(detector->sessionDynamic(2), box, reach);
    EXPECT_GT(on_box_0, 50u) << what << ": session 0's box is its dynamic part";
    EXPECT_EQ(on_box_1, 0u) << what << ": session 1 saw only the floor there";
    EXPECT_GT(on_box_2, 50u) << what << ": the box came back in session 2";
    const LabelMap p0 = detector->sessionDynamic(0);
    EXPECT_EQ(p0.count(VoxelLabel::kDynamic), on_box_0) << what << ": nothing else moved";
  }
}

TEST(ChangePipeline, DeviceMatchesReferenceForEveryKernelSize) {
  const sim::AnalyticDataset a = test::analyticSession({floorBox(-1.0, -0.3, 0.15)}, 6);
  const sim::AnalyticDataset b = test::analyticSession({floorBox(-0.2, -0.8, 0.12)}, 6);
  const MapConfig map = test::testMapConfig(0.04f, false);
  for (const auto& [erosion, dilation] : {std::pair{1, 1}, std::pair{3, 7}, std::pair{7, 3}}) {
    change::ChangeConfig config = test::testChangeConfig(0.04f);
    config.erosion_kernel_voxels = erosion;
    config.dilation_kernel_voxels = dilation;
    ChangeDetector device(test::sharedContext(), map, config);
    ChangeDetector reference(map, config);
    runSessions(device, reference, {&a, &b});
    const std::string what = "kernels " + std::to_string(erosion) + "/" + std::to_string(dilation);
    EXPECT_EQ(change::labelAgreement(device.labels(), reference.labels()), 1.0) << what;
    for (int i = 0; i < 2; ++i) {
      EXPECT_EQ(change::labelAgreement(device.sessionDynamic(i), reference.sessionDynamic(i)), 1.0)
          << what << ", session " << i;
    }
    EXPECT_GT(device.labels().count(VoxelLabel::kDynamic), 0u) << what;
  }
}

TEST(ChangePipeline, PartialOverlapMarksNothingOutsideWhatASessionSaw) {
  const auto world = test::roomWorld();
  sim::SimSessionConfig session_config;
  session_config.max_frames = 12;
  const MapConfig map = test::testMapConfig(0.05f, true);
  const change::ChangeConfig config = test::testChangeConfig(0.05f);
  ChangeDetector detector(test::sharedContext(), map, config);
  const sim::SimSessionDataset full(world, 0, session_config);
  const sim::SimSessionDataset later(world, 1, session_config);
  detector.beginSession();
  test::fuseSession(detector, 0, full, full.size());
  detector.endSession(0);
  const TsdfMap s_before = detector.staticMap();
  detector.beginSession();
  test::fuseSession(detector, 1, later, 3);  // the first quarter of the path only
  detector.endSession(1);
  const TsdfMap m1 = detector.sessionMap(1);
  const TsdfMap s_after = detector.staticMap();
  const float w = config.min_weight;
  std::size_t seen_by_1 = 0, changed_outside = 0;
  test::forEachVoxel(s_after, [&](const GlobalVoxelIndex& v, const TsdfVoxel& after) {
    if (test::observedIn(m1, v, w)) return void(++seen_by_1);
    const TsdfVoxel* before = s_before.findVoxel(v);
    const TsdfVoxel old = before != nullptr ? *before : TsdfVoxel{};
    if (old.tsdf_m != after.tsdf_m || old.weight != after.weight) ++changed_outside;
  });
  EXPECT_EQ(changed_outside, 0u) << "S changed where session 1 saw nothing";
  EXPECT_GT(seen_by_1, 1000u);
  const std::size_t outside_d = test::dynamicOutside(detector.labels(), m1, w);
  const std::size_t outside_p0 = test::dynamicOutside(detector.sessionDynamic(0), m1, w);
  const std::size_t outside_p1 = test::dynamicOutside(detector.sessionDynamic(1), m1, w);
  EXPECT_EQ(outside_d + outside_p0 + outside_p1, 0u) << "labelled where session 1 saw nothing";
  std::printf("[ change ] partial session: %zu voxels seen, D %llu dynamic\n", seen_by_1,
              (unsigned long long)detector.labels().count(VoxelLabel::kDynamic));
}

TEST(ChangePipeline, MisuseIsAnInputError) {
  change::ChangeConfig bad;
  bad.erosion_kernel_voxels = 4;
  EXPECT_THROW(ChangeDetector(test::testMapConfig(0.05f, false), bad), InputError);
  bad = change::ChangeConfig{};
  bad.merge_close_m = bad.difference_threshold_m;
  EXPECT_THROW(ChangeDetector(test::testMapConfig(0.05f, false), bad), InputError);
  ChangeDetector detector(test::sharedContext(), test::testMapConfig(0.05f, false),
                          test::testChangeConfig(0.05f));
  const sim::AnalyticDataset data = test::analyticSession({}, 2);
  EXPECT_THROW(detector.integrate(0, data.load(0), data.intrinsics()), InputError);
  detector.beginSession();
  detector.beginSession();
  EXPECT_THROW(detector.endSession(1), InputError) << "sessions end in order";
  EXPECT_THROW(detector.sessionDynamic(0), InputError) << "not ended yet";
  detector.integrate(1, data.load(0), data.intrinsics());  // any open session fuses
  detector.endSession(0);
  EXPECT_THROW(detector.integrate(0, data.load(1), data.intrinsics()), InputError);
  EXPECT_EQ(detector.sessionDynamic(0).count(VoxelLabel::kDynamic), 0u);
  EXPECT_THROW(detector.addSessionMap(TsdfMap(test::testMapConfig(0.04f, false))), InputError);
}

TEST(ChangePipeline, SubsampledSessionsNeedProportionallyFewerViews) {
  change::ChangeConfig config;  // min_weight 10: frames of a full-rate recording
  EXPECT_FLOAT_EQ(config.forSubsampling(1.0).min_weight, 10.0f);
  EXPECT_FLOAT_EQ(config.forSubsampling(5.0).min_weight, 2.0f) << "every 5th frame: 2 views";
  EXPECT_FLOAT_EQ(config.forSubsampling(5.0).difference_threshold_m,
                  config.difference_threshold_m);
  EXPECT_THROW(config.forSubsampling(0.5), InputError);
  EXPECT_THROW(config.forSubsampling(std::nan("")), InputError);
}

}  // namespace
}  // namespace strata

// Keyframe selection, the parts: the sparse raycast on the device against its reference
// and the full-image raycast, the metrics on constructed images, smoothing / selection /
// dilation / automatic thresholds, and bad input. The room experiment is test_select_room.cpp.
#include <gtest/gtest.h>

#include <cmath>

#include "strata/core/error.h"
#include "fusion_fixture.h"
#include "strata/raycast/raycast.h"
#include "strata/select/select_differences.h"
#include "strata/select/select_samples.h"
#include "strata/select/keyframe_scorer.h"
#include "strata/select/keyframe_selection.h"
#include "strata/select/eval/selection_eval.h"
#include "strata/sim/analytic_dataset.h"

namespace strata::selection {
namespace {

struct AnalyticMap {
  sim::AnalyticDataset dataset;
  std::unique_ptr<DeviceFusion> fusion;
  TsdfMap map;
};

/// The analytic room fused from 12 frames; made per test so no device object outlives the
/// shared context.
std::unique_ptr<AnalyticMap> analyticMap() {
  sim::AnalyticDatasetConfig config;
  config.frame_count = 24;
  auto out = std::make_unique<AnalyticMap>(
      AnalyticMap{sim::AnalyticDataset(config), nullptr, TsdfMap(MapConfig{})});
  out->fusion = std::make_unique<DeviceFusion>(test::sharedContext(), MapConfig{});
  out->map = test::fuseOnDevice(out->dataset, MapConfig{}, 24, 2, out->fusion.get());
  return out;
}

TEST(SelectSamples, DeviceMatchesReferenceAndFullRaycast) {
  const auto owned = analyticMap();
  AnalyticMap& m = *owned;
  SampleRaycastKernel kernel(test::sharedContext());
  const CameraIntrinsics k = m.dataset.intrinsics();
  std::size_t samples = 0, hit_mismatch = 0, depth_off = 0, color_off = 0, full_mismatch = 0;
  for (int pose : {3, 5, 11, 17}) {
    const Eigen::Isometry3d& T_W_C = m.dataset.poses()[pose];
    const SampleRaycast device = kernel.run(m.fusion->map(), k, T_W_C, 10);
    const SampleRaycast reference = raycastSamplesReference(m.map, k, T_W_C, 10);
    ASSERT_EQ(device.grid.count(), 64 * 48);
    for (int i = 0; i < device.grid.count(); ++i) {
      ++samples;
      hit_mismatch += device.hit[i] != reference.hit[i];
      if (device.hit[i] && reference.hit[i]) {
        depth_off += std::abs(device.depth_m[i] - reference.depth_m[i]) > 1e-3f;
        color_off += device.color_rgba[i] != reference.color_rgba[i];
      }
    }
    // Stride 1 is the full raycast: compare the sparse reference at its pixels with it.
    const RaycastImage full = raycastReference(m.map, k, T_W_C);
    for (int gy = 0; gy < reference.grid.height; ++gy) {
      for (int gx = 0; gx < reference.grid.width; ++gx) {
        const std::size_t p = static_cast<std::size_t>(reference.grid.pixelV(gy)) * k.width_px +
                              reference.grid.pixelU(gx);
        full_mismatch += full.hit[p] != reference.hit[gy * reference.grid.width + gx];
      }
    }
  }
  EXPECT_LE(hit_mismatch, samples / 1000) << "hit masks must agree on >= 99.9 % of samples";
  EXPECT_LE(depth_off, samples / 1000);
  EXPECT_LE(color_off, samples / 100);
  EXPECT_EQ(full_mismatch, 0u);
}

// sample_differences.comp against its reference on the same device samples, with a change put
// into the keyframe: a red box 0.4 m nearer over the left tenth of the image; the rest unchanged.
TEST(SelectDifferences, DeviceMatchesReferenceAndSeesTheChange) {
  const auto owned = analyticMap();
  AnalyticMap& m = *owned;
  KeyframeScorer scorer(test::sharedContext());
  const CameraIntrinsics k = m.dataset.intrinsics();
  const SampleDifferenceOptions options = differenceOptions(scorer.config());
  std::size_t compared = 0, color_off = 0, depth_off = 0, applies_off = 0;
  for (int pose : {3, 11, 17}) {
    RgbdFrame frame = m.dataset.load(pose);
    ASSERT_FALSE(frame.color.empty());
    for (int v = 0; v < k.height_px; ++v) {
      for (int u = 0; u < k.width_px / 10; ++u) {
        const std::size_t p = static_cast<std::size_t>(v) * k.width_px + u;
        if (frame.depth.depth_m[p] > 0.0f) frame.depth.depth_m[p] -= 0.4f;
        frame.color.rgb[p * 3] = 220, frame.color.rgb[p * 3 + 1] = 30,
                            frame.color.rgb[p * 3 + 2] = 30;
      }
    }
    SampleRaycast samples;
    SampleDifferences device;
    const KeyframeScore device_score =
        scorer.score(m.fusion->map(), frame, k, nullptr, &samples, &device);
    const SampleDifferences reference = sampleDifferencesReference(samples, frame, options);
    const KeyframeScore reference_score = scoreSamples(samples, frame, scorer.config());
    ASSERT_EQ(device.color.size(), reference.color.size());
    double changed_depth = 0.0, unchanged_depth = 0.0;
    int changed = 0, unchanged = 0;
    for (std::size_t i = 0; i < device.color.size(); ++i) {
      ++compared;
      applies_off += (device.color[i] < 0.0f) != (reference.color[i] < 0.0f) ||
                     (device.depth_m[i] < 0.0f) != (reference.depth_m[i] < 0.0f);
      color_off += std::abs(device.color[i] - reference.color[i]) > 1e-5f;
      depth_off += std::abs(device.depth_m[i] - reference.depth_m[i]) > 1e-5f;
      if (reference.depth_m[i] < 0.0f) continue;
      const int gx = static_cast<int>(i) % samples.grid.width;
      // Ground truth: exact depth, so only the changed strip differs (0.4 m - 5 cm tolerance).
      if (samples.grid.pixelU(gx) < k.width_px / 10) {
        changed_depth += reference.depth_m[i], ++changed;
      } else {
        unchanged_depth += reference.depth_m[i], ++unchanged;
      }
    }
    ASSERT_GT(changed, 0);
    EXPECT_NEAR(changed_depth / changed, 0.35, 0.03) << "pose " << pose;
    EXPECT_LT(unchanged_depth / unchanged, 0.005) << "pose " << pose;
    EXPECT_NEAR(device_score.color_change, reference_score.color_change, 1e-5);
    EXPECT_NEAR(device_score.depth_change_m, reference_score.depth_change_m, 1e-5);
    EXPECT_GT(device_score.color_change, 0.01);
  }
  EXPECT_EQ(applies_off, 0u);
  EXPECT_EQ(color_off, 0u) << "of " << compared << " samples";
  EXPECT_EQ(depth_off, 0u) << "of " << compared << " samples";
}

// The surface check of raycast_samples.comp against its reference, and both against the change
// put into the frame: the left tenth of the image 0.4 m nearer (off the map's surface by far more
// than the 2-voxel tolerance), the rest the exact depth of the fused scene (held).
TEST(SelectSamples, SurfaceCheckMatchesReferenceAndSeesTheChange) {
  const auto owned = analyticMap();
  AnalyticMap& m = *owned;
  SampleRaycastKernel kernel(test::sharedContext());
  const CameraIntrinsics k = m.dataset.intrinsics();
  const ScorerConfig config;
  std::size_t compared = 0, mismatched = 0;
  for (int pose : {3, 11, 17}) {
    RgbdFrame frame = m.dataset.load(pose);
    for (int v = 0; v < k.height_px; ++v) {
      for (int u = 0; u < k.width_px / 10; ++u) {
        float& d = frame.depth.depth_m[static_cast<std::size_t>(v) * k.width_px + u];
        if (d > 0.0f) d -= 0.4f;
      }
    }
    const SampleGrid grid = SampleGrid::of(k, 10);
    const MeasuredSamples measured =
        measuredSamples(grid, frame, config, m.map.config().voxel_size_m);
    const SampleRaycast device =
        kernel.run(m.fusion->map(), k, frame.T_W_C, 10, {}, nullptr, &measured);
    const SampleRaycast reference =
        raycastSamplesReference(m.map, k, frame.T_W_C, 10, {}, &measured);
    int changed = 0, changed_not_held = 0, unchanged = 0, unchanged_not_held = 0;
    for (int i = 0; i < grid.count(); ++i) {
      ++compared;
      mismatched += device.surface[i] != reference.surface[i];
      if (reference.surface[i] == SurfaceCheck::kNoMeasurement) continue;
      const bool not_held = reference.surface[i] == SurfaceCheck::kNotHeld;
      if (grid.pixelU(i % grid.width) < k.width_px / 10) {
        ++changed, changed_not_held += not_held;
      } else {
        ++unchanged, unchanged_not_held += not_held;
      }
    }
    ASSERT_GT(changed, 0);
    EXPECT_GE(changed_not_held, changed * 95 / 100) << "pose " << pose;
    EXPECT_LE(unchanged_not_held, unchanged / 50) << "pose " << pose;
  }
  EXPECT_LE(mismatched, compared / 1000) << "surface checks must agree on >= 99.9 % of samples";
  // Without measured depth nothing is checked.
  const SampleRaycast none = kernel.run(m.fusion->map(), k, m.dataset.poses()[3], 10);
  for (SurfaceCheck c : none.surface) ASSERT_EQ(c, SurfaceCheck::kNoMeasurement);
  MeasuredSamples wrong_size;
  wrong_size.depth_m.assign(5, 1.0f);
  EXPECT_THROW(kernel.run(m.fusion->map(), k, m.dataset.poses()[3], 10, {}, nullptr, &wrong_size),
               InputError);
  EXPECT_THROW(raycastSamplesReference(m.map, k, m.dataset.poses()[3], 10, {}, &wrong_size),
               InputError);
}

TEST(SelectScorer, OwnFramesAreCoveredAndUnchanged) {
  const auto owned = analyticMap();
  AnalyticMap& m = *owned;
  KeyframeScorer scorer(test::sharedContext());
  const RgbdFrame frame = m.dataset.load(4);  // fused above
  const KeyframeScore device = scorer.score(m.fusion->map(), frame, m.dataset.intrinsics());
  const KeyframeScore reference = scoreKeyframeReference(m.map, frame, m.dataset.intrinsics());
  EXPECT_GT(device.coverage, 0.95);
  EXPECT_LT(device.depth_change_m, 0.02);
  EXPECT_LT(device.surface_change, 0.02);
  EXPECT_GT(device.ncc, 0.8);
  EXPECT_NEAR(device.coverage, reference.coverage, 1e-3);
  EXPECT_NEAR(device.color_change, reference.color_change, 1e-2);
  EXPECT_NEAR(device.depth_change_m, reference.depth_change_m, 1e-3);
  EXPECT_NEAR(device.surface_change, reference.surface_change, 1e-3);
}

/// Samples that all hit at 2 m with a grey-blue colour, and a frame seeing the same.
struct Constructed {
  SampleRaycast rendered;
  RgbdFrame frame;
};

Constructed constructed(const CameraIntrinsics& k) {
  Constructed c;
  c.rendered.grid = SampleGrid::of(k, 10);
  const std::size_t n = c.rendered.grid.count();
  c.rendered.hit.assign(n, 1);
  c.rendered.depth_m.assign(n, 2.0f);
  c.rendered.color_rgba.assign(n, packRgb(100, 120, 140));
  c.frame.depth = DepthImage(k.width_px, k.height_px, 2.0f);
  c.frame.color = ColorImage(k.width_px, k.height_px);
  for (std::size_t p = 0; p < c.frame.color.rgb.size(); p += 3) {
    c.frame.color.rgb[p] = 100, c.frame.color.rgb[p + 1] = 120, c.frame.color.rgb[p + 2] = 140;
  }
  return c;
}

TEST(SelectScorer, MetricsOnConstructedImages) {
  const CameraIntrinsics k;
  Constructed c = constructed(k);
  const ScorerConfig config;
  KeyframeScore same = scoreSamples(c.rendered, c.frame, config);
  EXPECT_DOUBLE_EQ(same.coverage, 1.0);
  EXPECT_NEAR(same.color_change, 0.0, 1e-6);
  EXPECT_NEAR(same.depth_change_m, 0.0, 1e-6);

  // A light change that shades surfaces differently (left half 30 % brighter, right half 30 %
  // darker) is normalised away.
  Constructed relit = constructed(k);
  for (std::size_t p = 0; p < relit.frame.color.rgb.size(); ++p) {
    const bool left = (p / 3) % 640 < 320;
    relit.frame.color.rgb[p] =
        static_cast<std::uint8_t>(relit.frame.color.rgb[p] * (left ? 1.3 : 0.7));
  }
  EXPECT_LT(scoreSamples(relit.rendered, relit.frame, config).color_change, 0.01);

  // A red object over 10 % of the image, 0.5 m nearer; a quarter of the samples miss.
  Constructed changed = constructed(k);
  for (int v = 0; v < 480; ++v) {
    for (int u = 0; u < 64; ++u) {
      const std::size_t p = static_cast<std::size_t>(v) * 640 + u;
      changed.frame.depth.depth_m[p] = 1.5f;
      changed.frame.color.rgb[p * 3] = 220, changed.frame.color.rgb[p * 3 + 1] = 30;
    }
  }
  for (std::size_t i = 0; i < changed.rendered.hit.size() / 4; ++i) changed.rendered.hit[i] = 0;
  const KeyframeScore s = scoreSamples(changed.rendered, changed.frame, config);
  EXPECT_NEAR(s.coverage, 0.75, 0.01);
  EXPECT_GT(s.color_change, 0.05);
  // ~9.4 % of the hit samples 0.45 m beyond the 5 cm tolerance, over the upper half: ~0.085 m.
  EXPECT_NEAR(s.depth_change_m, 0.085, 0.01);
  EXPECT_LT(s.ncc, same.ncc);
}

std::vector<KeyframeScore> flatScores(std::size_t n) {
  std::vector<KeyframeScore> s(n);
  for (auto& k : s) k.coverage = 1.0, k.ncc = k.histogram = 1.0;
  return s;
}

TEST(SelectSelection, SmoothsThresholdsAndDilates) {
  EXPECT_EQ(movingAverage({0, 0, 5, 0, 0}, 5),
            (std::vector<double>{5.0 / 3, 1.25, 1, 1.25, 5.0 / 3}));
  std::vector<KeyframeScore> scores = flatScores(20);
  scores[10].depth_change_m = 0.5;  // one strong change: smoothed 0.1 over frames 8..12
  SelectionConfig config;
  config.thresholds.depth_change_m = 0.09;
  config.thresholds.color_change = -1.0;  // unused
  TrajectorySelection s = selectKeyframes(scores, config);
  for (std::size_t i = 0; i < 20; ++i) {
    EXPECT_EQ(s.triggered[i], i >= 8 && i <= 12) << i;
    EXPECT_EQ(s.selected[i], i >= 7 && i <= 13) << i;
  }
  config.smoothing_window = 1;
  config.dilation = 0;
  EXPECT_EQ(selectKeyframes(scores, config).selectedCount(), 1u);
  scores[3].coverage = 0.2;
  EXPECT_EQ(selectKeyframes(scores, config).selectedCount(), 2u);
  scores[17].surface_change = 0.05;  // 5 % of its measured samples off the map's surface
  EXPECT_EQ(selectKeyframes(scores, config).selectedCount(), 3u);
  config.thresholds.surface_change = -1.0;  // unused
  EXPECT_EQ(selectKeyframes(scores, config).selectedCount(), 2u);
  config.method = Method::kNcc;
  scores[15].ncc = -0.5;
  EXPECT_EQ(selectKeyframes(scores, config).selectedCount(), 1u);
}

TEST(SelectSelection, AutoThresholdsAreTheFirstSessionExtremes) {
  std::vector<KeyframeScore> first = flatScores(9);
  for (std::size_t i = 0; i < first.size(); ++i) {
    first[i].color_change = 0.1 + 0.01 * i;
    first[i].depth_change_m = 0.01;
    first[i].coverage = 0.97;
    first[i].ncc = 0.9;
  }
  std::vector<KeyframeScore> thin_parts_lost = first;
  thin_parts_lost[4].surface_change = 0.09;
  EXPECT_NEAR(autoThresholds(thin_parts_lost, 1).surface_change, Thresholds{}.surface_change, 1e-12)
      << "kept, not estimated";
  const Thresholds t = autoThresholds(first, 1);
  EXPECT_NEAR(t.color_change, 0.18, 1e-9);
  EXPECT_NEAR(t.depth_change_m, 0.01, 1e-9);
  EXPECT_NEAR(t.coverage, 0.97, 1e-9);
  EXPECT_NEAR(t.ncc, 0.9, 1e-9);
  // The first session never selects itself with its own thresholds.
  SelectionConfig config;
  config.smoothing_window = 1;
  config.thresholds = t;
  EXPECT_EQ(selectKeyframes(first, config).selectedCount(), 0u);
}

TEST(SelectSelection, ConfusionCounts) {
  std::vector<KeyframeTruth> truth(4);
  truth[0].positive = truth[1].positive = true;
  const Confusion c = confusion({1, 0, 1, 0}, truth);
  EXPECT_EQ(c.true_positive, 1);
  EXPECT_EQ(c.false_negative, 1);
  EXPECT_EQ(c.false_positive, 1);
  EXPECT_EQ(c.true_negative, 1);
  EXPECT_DOUBLE_EQ(c.accuracy(), 0.5);
}

TEST(SelectInput, BadInputNamesTheProblem) {
  const auto owned = analyticMap();
  AnalyticMap& m = *owned;
  const CameraIntrinsics k = m.dataset.intrinsics();
  EXPECT_THROW(SampleGrid::of(k, 0), InputError);
  Eigen::Isometry3d nan_pose = Eigen::Isometry3d::Identity();
  nan_pose(0, 3) = NAN;
  EXPECT_THROW(raycastSamplesReference(m.map, k, nan_pose, 10), InputError);
  KeyframeScorer scorer(test::sharedContext());
  RgbdFrame frame = m.dataset.load(0);
  frame.T_W_C = nan_pose;
  EXPECT_THROW(scorer.score(m.fusion->map(), frame, k), InputError);
  frame = m.dataset.load(0);
  frame.depth = DepthImage(320, 240);
  try {
    scorer.score(m.fusion->map(), frame, k);
    FAIL() << "a 320x240 frame for a 640x480 camera was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("320x240"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseMethod("sift"), InputError);
  SelectionConfig even;
  even.smoothing_window = 4;
  EXPECT_THROW(selectKeyframes(flatScores(3), even), InputError);
}

}  // namespace
}  // namespace strata::selection

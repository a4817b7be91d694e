// The changed views of skipped keyframes (select/changed_views.h): the samples that look beyond
// the map (vacated) or measure something new in front of it (arrived), the depth kept around
// them, vacated places shared among keyframes, which rays pass a point, and bad input. Also the
// points a keyframe confirmed (select/confirmed_points.h). Constructed frames: cameras looking
// along +z at a wall 2 m away, side by side along x.
#include <gtest/gtest.h>

#include <cmath>

#include "strata/core/error.h"
#include "strata/select/changed_views.h"
#include "strata/select/confirmed_points.h"

namespace strata::selection {
namespace {

CameraIntrinsics camera() {
  CameraIntrinsics k;
  k.width_px = 160;
  k.height_px = 120;
  k.fx_px = k.fy_px = 100.0f;
  k.cx_px = 79.5f;
  k.cy_px = 59.5f;
  return k;
}

/// A camera at x = `x_m` looking along +z at a wall at z = 2 m (or turned away from it).
RgbdFrame wallFrame(double x_m, bool facing_wall = true) {
  const CameraIntrinsics k = camera();
  RgbdFrame f;
  f.depth = DepthImage(k.width_px, k.height_px, 2.0f);
  f.T_W_C = Eigen::Isometry3d::Identity();
  f.T_W_C.translation() = Eigen::Vector3d(x_m, 0.0, 0.0);
  if (!facing_wall) f.T_W_C.linear() = Eigen::AngleAxisd(M_PI, Eigen::Vector3d::UnitY()).matrix();
  return f;
}

TEST(ChangedViews, VacatedSamplesAreWhereTheKeyframeSeesBeyondTheMapsSurface) {
  const ChangedViewConfig config;
  const RgbdFrame frame = wallFrame(0.0);  // measures the wall at 2 m everywhere
  SampleRaycast samples;
  samples.grid = SampleGrid::of(camera(), 40);  // 4 x 3 samples
  const std::size_t n = samples.grid.count();
  samples.hit.assign(n, 1);
  samples.depth_m.assign(n, 2.0f);  // the map holds the wall ...
  samples.depth_m[5] = 1.5f;        // ... and, on two samples, an object in front of it
  samples.depth_m[6] = 1.95f;       // (this one within the tolerance: noise, not vacated)
  samples.hit[7] = 0, samples.depth_m[7] = 0.0f;  // a miss is new space, not a vacated place
  const change::ChangedView view = changedView(samples, frame, config);
  ASSERT_EQ(view.samples.size(), 1u);
  const SampleGrid& g = samples.grid;
  EXPECT_EQ(view.samples[0].u_px, g.pixelU(5 % g.width));
  EXPECT_EQ(view.samples[0].v_px, g.pixelV(5 / g.width));
  EXPECT_FLOAT_EQ(view.samples[0].surface_m, 1.5f);  // the map's surface on its ray
  ASSERT_EQ(view.arrived.size(), 1u) << "the miss where the keyframe measures the wall";
  EXPECT_EQ(view.arrived[0].u_px, g.pixelU(7 % g.width));
  const std::vector<Eigen::Vector3f> points = change::samplePoints(view, camera());
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].z(), 1.5f, 1e-5f);
  const float u = static_cast<float>(g.pixelU(5 % g.width)), v = g.pixelV(5 / g.width);
  EXPECT_NEAR(points[0].x(), (u - camera().cx_px) / camera().fx_px * 1.5f, 1e-5f);
  EXPECT_NEAR(points[0].y(), (v - camera().cy_px) / camera().fy_px * 1.5f, 1e-5f);
  EXPECT_TRUE(passesPoint(frame, camera(), points[0], config));
}

TEST(ChangedViews, AVacatedViewKeepsTheSampleAndTheDepthAroundIt) {
  const ChangedViewConfig config;
  RgbdFrame frame = wallFrame(0.0);
  for (int v = 0; v < camera().height_px; ++v) {
    for (int u = 0; u < camera().width_px; ++u)
      frame.depth.at(u, v) = 2.0f + 0.0005f * u;  // within the tolerance
  }
  SampleRaycast samples;
  samples.grid = SampleGrid::of(camera(), 40);  // 4 x 3 samples, cells of 40 px
  const std::size_t n = samples.grid.count();
  samples.hit.assign(n, 1);
  samples.depth_m.assign(n, 2.0f);
  samples.depth_m[5] = 1.5f;  // sample (1, 1), pixel (60, 60): an object stood there
  for (const float radius_m : {0.05f, 0.3f}) {
    change::FreeSpaceConfig free_space;
    free_space.cell_px = 40;
    free_space.place_radius_m = radius_m;
    change::ChangedView view = changedView(samples, frame, config);
    EXPECT_EQ(view.depth.tileCount(), 0u) << "no depth until the loop knows it is skipped";
    EXPECT_EQ(view.depth.tilePx(), 40) << "tiles of the grid's cells";
    change::keepDepthAround(frame.depth, camera(), free_space, view);
    const bool small = radius_m < 0.1f;
    ASSERT_EQ(view.samples.size(), 1u);
    EXPECT_EQ(view.samples[0].u_px, 60);
    EXPECT_EQ(view.samples[0].v_px, 60);
    EXPECT_FLOAT_EQ(view.samples[0].surface_m, 1.5f);
    EXPECT_TRUE(view.T_W_C.isApprox(frame.T_W_C.cast<float>()));
    // Where the place can project: within 100 * 0.05 / 1.45 = 3.4 px, inside its cell (pixels
    // 40..79); within 100 * 0.3 / 1.2 = 25 px, on the 3 x 3 cells around it.
    EXPECT_EQ(view.depth.tileCount(), small ? 1u : 9u);
    EXPECT_FLOAT_EQ(view.depth.at(40, 79), frame.depth.at(40, 79));
    EXPECT_EQ(std::isnan(view.depth.at(39, 60)), small);
    EXPECT_EQ(std::isnan(view.depth.at(119, 119)), small);
    EXPECT_TRUE(std::isnan(view.depth.at(120, 60)));
  }
}

TEST(ChangedViews, AViewKeepsTheSamplesThatMeasureSomethingNewInFrontOfTheMap) {
  const ChangedViewConfig config;
  RgbdFrame frame = wallFrame(0.0);  // the wall at 2 m, as the map holds it
  SampleRaycast samples;
  samples.grid = SampleGrid::of(camera(), 40);  // 4 x 3 samples, cells of 40 px
  const SampleGrid& g = samples.grid;
  const std::size_t n = g.count();
  samples.hit.assign(n, 1);
  samples.depth_m.assign(n, 2.0f);
  const auto measure = [&](std::size_t s, float depth_m) {
    frame.depth.at(g.pixelU(static_cast<int>(s) % g.width),
                   g.pixelV(static_cast<int>(s) / g.width)) = depth_m;
  };
  measure(5, 1.5f);                               // something arrived in front of the wall
  measure(6, 1.95f);                              // within the tolerance: noise
  samples.hit[7] = 0, samples.depth_m[7] = 0.0f;  // the map has nothing on this ray ...
  measure(7, 3.0f);                               // ... and the keyframe measures something
  samples.hit[8] = 0, samples.depth_m[8] = 0.0f;
  measure(8, 9.0f);  // beyond the fusion's range: nothing fusion would use
  measure(9, 0.0f);  // no depth
  measure(10, NAN);  // no depth either
  const change::ChangedView view = changedView(samples, frame, config);
  EXPECT_TRUE(view.samples.empty()) << "nothing measured beyond the map";
  ASSERT_EQ(view.arrived.size(), 2u);
  EXPECT_EQ(view.arrived[0].u_px, 60);
  EXPECT_EQ(view.arrived[0].v_px, 60);
  EXPECT_FLOAT_EQ(view.arrived[0].measured_m, 1.5f);
  EXPECT_EQ(view.arrived[1].u_px, 140);
  EXPECT_EQ(view.arrived[1].v_px, 60);
  EXPECT_FLOAT_EQ(view.arrived[1].measured_m, 3.0f);
  // Its depth is kept on its cell and the ring of cells around it; ring 0 keeps none.
  for (const int ring : {0, 1}) {
    change::FreeSpaceConfig free_space;
    free_space.cell_px = 40;
    free_space.arrived_ring_cells = ring;
    change::ChangedView kept = view;
    change::keepDepthAround(frame.depth, camera(), free_space, kept);
    // Samples (1, 1) and (3, 1) of a 4 x 3 grid: 3 x 3 cells and 2 x 3 cells, sharing 1 x 3.
    EXPECT_EQ(kept.depth.tileCount(), ring == 0 ? 0u : 12u) << ring;
    if (ring == 1) {
      EXPECT_FLOAT_EQ(kept.depth.at(0, 0), frame.depth.at(0, 0));
      EXPECT_FLOAT_EQ(kept.depth.at(60, 60), 1.5f);
      EXPECT_FLOAT_EQ(kept.depth.at(159, 119), frame.depth.at(159, 119));
    }
  }
}

TEST(ChangedViews, SkippedKeyframesTakeTheVacatedPlacesTheyLookThrough) {
  const ChangedViewConfig config;
  const CameraIntrinsics k = camera();
  // Keyframe 0 found a vacated place: at pixel (60, 60) the map's surface stood at 1.5 m, in
  // front of the wall it measures at 2 m. Keyframe 1 (0.3 m to the side) looks through that
  // place too; keyframe 2 sees a new object in front of it; keyframe 3 looks away.
  std::vector<RgbdFrame> frames{wallFrame(0.0), wallFrame(0.3), wallFrame(0.3),
                                wallFrame(0.0, false)};
  for (int v = 0; v < k.height_px; ++v) {
    for (int u = 0; u < k.width_px; ++u) frames[2].depth.at(u, v) = 1.45f;
  }
  std::vector<change::ChangedView> views(frames.size());
  for (std::size_t i = 0; i < frames.size(); ++i) {
    views[i].T_W_C = frames[i].T_W_C.cast<float>();
    views[i].depth = change::DepthTiles(10);
  }
  views[0].samples = {{60, 60, 1.5f}, {60, 60, 1.5f}};  // the same place twice: shared once
  change::FreeSpaceConfig free_space;
  free_space.place_radius_m = 0.05f;  // 100 * 0.05 / 1.45: 4 px around, inside one cell
  const std::size_t added = shareVacatedPlaces(views, frames, {1, 1, 1, 1}, k, config, 10);
  EXPECT_EQ(added, 1u);
  ASSERT_EQ(views[1].samples.size(), 1u);
  EXPECT_TRUE(views[2].samples.empty()) << "measured in front of the place: not looked through";
  EXPECT_TRUE(views[3].samples.empty()) << "behind the camera";
  // The point (x -0.3 m from keyframe 1 at z 1.5) projects to u = 60 - 0.3 / 1.5 * 100 = 40:
  // cell 4, centre 45.
  EXPECT_EQ(views[1].samples[0].u_px, 45);
  EXPECT_EQ(views[1].samples[0].v_px, 65);
  EXPECT_NEAR(views[1].samples[0].surface_m, 1.5f, 1e-5f);
  EXPECT_EQ(views[1].depth.tileCount(), 0u) << "sharing keeps no depth itself";
  change::keepDepthAround(frames[1].depth, k, free_space, views[1]);
  EXPECT_EQ(views[1].depth.tileCount(), 1u) << "the depth of its cell is kept";
  EXPECT_FLOAT_EQ(views[1].depth.at(45, 65), 2.0f);
  EXPECT_EQ(views[0].samples.size(), 2u) << "a view does not take its own samples again";
  // Views that are not targets take nothing; mismatched lists are named.
  std::vector<change::ChangedView> again = views;
  again[1].samples.clear();
  EXPECT_EQ(shareVacatedPlaces(again, frames, {0, 0, 0, 0}, k, config, 10), 0u);
  EXPECT_TRUE(again[1].samples.empty());
  EXPECT_THROW(shareVacatedPlaces(again, frames, {1, 1}, k, config, 10), InputError);
  EXPECT_THROW(shareVacatedPlaces(again, frames, {1, 1, 1, 1}, k, config, 0), InputError);
}

TEST(ChangedViews, AKeyframePassesAPointWhenItMeasuresBeyondIt) {
  const ChangedViewConfig config;
  const RgbdFrame frame = wallFrame(0.0);
  EXPECT_TRUE(passesPoint(frame, camera(), {0.1f, 0.1f, 1.5f}, config));    // wall behind it
  EXPECT_FALSE(passesPoint(frame, camera(), {0.1f, 0.1f, 1.95f}, config));  // within tolerance
  EXPECT_FALSE(passesPoint(frame, camera(), {0.1f, 0.1f, 2.5f}, config));   // behind the wall
  EXPECT_FALSE(passesPoint(frame, camera(), {3.0f, 0.0f, 1.5f}, config));   // outside the image
  EXPECT_FALSE(passesPoint(frame, camera(), {0.0f, 0.0f, -1.5f}, config));  // behind the camera
  RgbdFrame none = wallFrame(0.0);
  none.depth = DepthImage(camera().width_px, camera().height_px, 0.0f);  // no depth
  EXPECT_FALSE(passesPoint(none, camera(), {0.1f, 0.1f, 1.5f}, config));
  RgbdFrame far = wallFrame(0.0);
  far.depth = DepthImage(camera().width_px, camera().height_px, 7.0f);  // beyond fusion's range
  EXPECT_FALSE(passesPoint(far, camera(), {0.1f, 0.1f, 1.5f}, config));
}

TEST(ChangedViews, BadInputNamesTheProblem) {
  ChangedViewConfig config;
  config.depth_tolerance_m = std::nanf("");
  EXPECT_THROW(config.validate(), InputError);
  config = {};
  config.max_depth_m = 0.05f;
  EXPECT_THROW(config.validate(), InputError);
  config = {};
  const std::vector<RgbdFrame> frames = {wallFrame(0.0)};
  std::vector<change::ChangedView> views(2);
  try {
    shareVacatedPlaces(views, frames, {1}, camera(), config, 10);
    ADD_FAILURE() << "lengths differ";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("one each per keyframe"), std::string::npos) << e.what();
  }
}

TEST(ConfirmedPoints, AreTheMeasuredPointsTheMapHoldsWhereItsSurfaceIsAtTheMeasuredDepth) {
  const CameraIntrinsics k = camera();
  RgbdFrame frame = wallFrame(1.0);  // the wall 2 m ahead
  SampleRaycast samples;
  samples.grid = SampleGrid::of(k, 40);  // 4 x 3 samples
  const std::size_t n = samples.grid.count();
  samples.hit.assign(n, 1);
  samples.depth_m.assign(n, 2.02f);
  samples.surface.assign(n, SurfaceCheck::kHeld);
  samples.hit[0] = 0;                                 // a miss
  samples.surface[1] = SurfaceCheck::kNotHeld;        // the map does not hold the measured point
  samples.surface[2] = SurfaceCheck::kNoMeasurement;  // no depth there
  samples.depth_m[3] = 1.5f;                          // something in front of the measured wall
  const SampleGrid& g = samples.grid;
  frame.depth.at(g.pixelU(4 % g.width), g.pixelV(4 / g.width)) = 7.0f;  // beyond fusion's range
  ConfirmConfig config;
  config.min_radius_m = 0.01f;
  const std::vector<change::ConfirmedPoint> points = confirmedPoints(samples, frame, k, config);
  ASSERT_EQ(points.size(), n - 5);
  const float u = static_cast<float>(g.pixelU(5 % g.width)), v = g.pixelV(5 / g.width);
  EXPECT_NEAR(points[0].p_W.z(), 2.0f, 1e-5f);  // the measured point, not the rendered one
  EXPECT_NEAR(points[0].p_W.x(), 1.0f + (u - k.cx_px) / k.fx_px * 2.0f, 1e-5f);
  EXPECT_NEAR(points[0].p_W.y(), (v - k.cy_px) / k.fy_px * 2.0f, 1e-5f);
  EXPECT_NEAR(points[0].radius_m, 0.75f * 40 * 2.0f / 100.0f, 1e-5f);  // 0.75 x the spacing
  config.radius_scale = 0.0f;                                          // the minimum then applies
  EXPECT_FLOAT_EQ(confirmedPoints(samples, frame, k, config)[0].radius_m, 0.01f);
}

TEST(ConfirmedPoints, RejectBadInput) {
  const CameraIntrinsics k = camera();
  const RgbdFrame frame = wallFrame(0.0);
  SampleRaycast samples;
  samples.grid = SampleGrid::of(k, 40);
  samples.hit.assign(samples.grid.count(), 1);
  samples.depth_m.assign(samples.grid.count(), 2.0f);  // no surface checks
  EXPECT_THROW(confirmedPoints(samples, frame, k, ConfirmConfig{}), InputError);
  ConfirmConfig bad;
  bad.depth_tolerance_m = NAN;
  EXPECT_THROW(bad.validate(), InputError);
  bad = ConfirmConfig{};
  bad.min_radius_m = -0.1f;
  EXPECT_THROW(bad.validate(), InputError);
}

}  // namespace
}  // namespace strata::selection

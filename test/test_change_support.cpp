// Views of vacated places for change detection (select/change_support.h): the vacated points of a
// keyframe's samples, which keyframes' rays pass a point, the greedy choice of the keyframes that
// give points short of views their rays, and bad input. Also the points a keyframe confirmed
// (select/confirmed_points.h). Constructed frames: cameras looking along
// +z at a wall 2 m away, side by side along x.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.h"
#include "select/change_support.h"
#include "select/confirmed_points.h"

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

/// `n` points 0.5 m in front of the wall around x = `x_m`: where a removed object stood.
std::vector<Eigen::Vector3f> vacated(float x_m, int n) {
  std::vector<Eigen::Vector3f> points;
  for (int i = 0; i < n; ++i) points.emplace_back(x_m + 0.01f * (i % 10), 0.01f * (i / 10), 1.5f);
  return points;
}

TEST(ChangeSupport, VacatedPointsAreTheMapsSurfaceWhereTheKeyframeSeesBeyondIt) {
  const SupportConfig config;
  const RgbdFrame frame = wallFrame(0.0);  // measures the wall at 2 m everywhere
  SampleRaycast samples;
  samples.grid = SampleGrid::of(camera(), 40);  // 4 x 3 samples
  const std::size_t n = samples.grid.count();
  samples.hit.assign(n, 1);
  samples.depth_m.assign(n, 2.0f);  // the map holds the wall ...
  samples.depth_m[5] = 1.5f;        // ... and, on two samples, an object in front of it
  samples.depth_m[6] = 1.95f;       // (this one within the tolerance: noise, not vacated)
  samples.hit[7] = 0, samples.depth_m[7] = 0.0f;  // a miss is new space, not a vacated place
  const std::vector<Eigen::Vector3f> points = vacatedPoints(samples, frame, camera(), config);
  ASSERT_EQ(points.size(), 1u);
  EXPECT_NEAR(points[0].z(), 1.5f, 1e-5f);  // on the map's surface, on sample 5's ray
  const SampleGrid& g = samples.grid;
  const float u = static_cast<float>(g.pixelU(5 % g.width)), v = g.pixelV(5 / g.width);
  EXPECT_NEAR(points[0].x(), (u - camera().cx_px) / camera().fx_px * 1.5f, 1e-5f);
  EXPECT_NEAR(points[0].y(), (v - camera().cy_px) / camera().fy_px * 1.5f, 1e-5f);
  EXPECT_TRUE(passesPoint(frame, camera(), points[0], config));
}

TEST(ChangeSupport, AVacatedViewKeepsTheSampleAndTheDepthAroundIt) {
  const SupportConfig config;
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

TEST(ChangeSupport, AViewKeepsTheSamplesThatMeasureSomethingNewInFrontOfTheMap) {
  const SupportConfig config;
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

TEST(ChangeSupport, SkippedKeyframesTakeTheVacatedPlacesTheyLookThrough) {
  const SupportConfig config;
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

TEST(ChangeSupport, MinNeighboursKeepsAreasAndDropsLoneSamples) {
  const RgbdFrame frame = wallFrame(0.0);
  SampleRaycast samples;
  samples.grid = SampleGrid::of(camera(), 10);  // 16 x 12 samples
  const SampleGrid& g = samples.grid;
  const std::size_t n = g.count();
  samples.hit.assign(n, 1);
  samples.depth_m.assign(n, 2.0f);
  for (int gy = 2; gy <= 4; ++gy) {  // a 3 x 3 area in front of the wall: a vacated place
    for (int gx = 2; gx <= 4; ++gx) samples.depth_m[gy * g.width + gx] = 1.5f;
  }
  samples.depth_m[9 * g.width + 12] = 1.5f;  // a lone sample
  SupportConfig config;
  EXPECT_EQ(vacatedPoints(samples, frame, camera(), config).size(), 10u);
  config.min_neighbours = 3;  // corners of the area have 3, edges 5, the centre 8
  EXPECT_EQ(vacatedPoints(samples, frame, camera(), config).size(), 9u);
  config.min_neighbours = 4;
  EXPECT_EQ(vacatedPoints(samples, frame, camera(), config).size(), 5u);
  config.min_neighbours = 9;
  EXPECT_THROW(config.validate(), InputError);
}

TEST(ChangeSupport, AKeyframePassesAPointWhenItMeasuresBeyondIt) {
  const SupportConfig config;
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

TEST(ChangeSupport, AddsTheKeyframesThatPassTheVacatedPlaceUntilItHasItsViews) {
  // Keyframe 0 (selected) saw 100 vacated points at x = 0; keyframes 1-3 pass them too, 4 and 5
  // look the other way.
  const std::vector<RgbdFrame> frames = {wallFrame(0.0),        wallFrame(0.1),
                                         wallFrame(0.2),        wallFrame(0.3),
                                         wallFrame(0.0, false), wallFrame(0.1, false)};
  std::vector<std::vector<Eigen::Vector3f>> points(frames.size());
  points[0] = vacated(0.0f, 100);
  points[2] = vacated(0.5f, 100);  // not selected: its points are not the selection's
  const std::vector<std::uint8_t> selected = {1, 0, 0, 0, 0, 0};
  SupportConfig config;
  config.views = 3;
  config.all_keyframes = false;
  const SupportResult r = supportViews(points, frames, camera(), selected, config);
  EXPECT_EQ(r.points, 100u);
  EXPECT_EQ(r.unsupported_before, 100u);
  EXPECT_EQ(r.unsupported_after, 0u);
  int added = 0;
  for (auto a : r.added) added += a;
  EXPECT_EQ(added, 2);  // two more views, no more
  EXPECT_EQ(r.added[0], 0);
  EXPECT_EQ(r.added[4] + r.added[5], 0);

  config.views = 5;  // only three keyframes besides keyframe 0 can pass it
  const SupportResult all = supportViews(points, frames, camera(), selected, config);
  EXPECT_EQ(all.added, (std::vector<std::uint8_t>{0, 1, 1, 1, 0, 0}));
  EXPECT_EQ(all.unsupported_after, 100u);

  config.views = 3;
  config.min_points = 101;  // no keyframe passes enough points
  const SupportResult none = supportViews(points, frames, camera(), selected, config);
  EXPECT_EQ(none.added, std::vector<std::uint8_t>(frames.size(), 0));
  EXPECT_EQ(none.unsupported_after, 100u);

  config.min_points = 30;
  config.views = 0;  // off
  const SupportResult off = supportViews(points, frames, camera(), selected, config);
  EXPECT_EQ(off.added, std::vector<std::uint8_t>(frames.size(), 0));
}

TEST(ChangeSupport, WithAllKeyframesTheVacatedPointsOfUnselectedOnesCountToo) {
  // As above, but keyframe 2's points (a place no selected keyframe measured beyond) count: the
  // views added then serve both places.
  const std::vector<RgbdFrame> frames = {wallFrame(0.0), wallFrame(0.1), wallFrame(0.2),
                                         wallFrame(0.3), wallFrame(0.0, false)};
  std::vector<std::vector<Eigen::Vector3f>> points(frames.size());
  points[0] = vacated(0.0f, 100);
  points[2] = vacated(0.5f, 100);
  const std::vector<std::uint8_t> selected = {1, 0, 0, 0, 0};
  SupportConfig config;
  config.views = 3;
  ASSERT_TRUE(config.all_keyframes);  // the default
  const SupportResult r = supportViews(points, frames, camera(), selected, config);
  EXPECT_EQ(r.points, 200u);
  EXPECT_EQ(r.unsupported_before, 200u);
  EXPECT_EQ(r.unsupported_after, 0u);
  EXPECT_EQ(r.added[1] + r.added[2] + r.added[3], 2);
  EXPECT_EQ(r.added[0] + r.added[4], 0);
  // Only keyframe 2's place: it is short of views although no keyframe was selected for it.
  points[0].clear();
  const SupportResult unselected = supportViews(points, frames, camera(), selected, config);
  EXPECT_EQ(unselected.points, 100u);
  EXPECT_EQ(unselected.unsupported_after, 0u);
  config.all_keyframes = false;
  EXPECT_EQ(supportViews(points, frames, camera(), selected, config).points, 0u);
}

TEST(ChangeSupport, BadInputNamesTheProblem) {
  const std::vector<RgbdFrame> frames = {wallFrame(0.0)};
  SupportConfig config;
  try {
    supportViews({}, frames, camera(), {1}, config);
    ADD_FAILURE() << "lengths differ";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("differ in length"), std::string::npos) << e.what();
  }
  config.views = -1;
  EXPECT_THROW(config.validate(), InputError);
  config = {};
  config.min_points = 0;
  EXPECT_THROW(config.validate(), InputError);
  config = {};
  config.depth_tolerance_m = std::nanf("");
  EXPECT_THROW(config.validate(), InputError);
  config = {};
  config.max_depth_m = 0.05f;
  EXPECT_THROW(config.validate(), InputError);
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

// Simulated sensors: RGB-D camera (exact depth, object ids, noise model), grey camera,
// trajectories, IMU, odometry drift and the deterministic random numbers behind them.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"
#include "sim/sensors/analytic_ray_scene.h"
#include "sim/sensors/grey_camera.h"
#include "sim/sensors/imu.h"
#include "sim/sensors/odometry_drift.h"
#include "sim/sensors/quintic_spline.h"
#include "sim/sensors/rgbd_camera.h"
#include "sim/rng.h"
#include "sim/sensors/trajectory.h"

namespace strata::sim {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Helpers: small cameras, scenes, and independent analytic ray casts in double precision.

CameraIntrinsics smallIntrinsics(int width, int height, float focal_px) {
  CameraIntrinsics k;
  k.width_px = width;
  k.height_px = height;
  k.fx_px = k.fy_px = focal_px;
  k.cx_px = 0.5f * (width - 1);
  k.cy_px = 0.5f * (height - 1);
  return k;
}

DepthNoiseConfig allEffectsOff() {
  DepthNoiseConfig n;
  n.axial_noise = n.grazing_dropout = n.dark_dropout = n.reflective_dropout = false;
  n.flying_pixels = n.quantize = false;
  return n;
}

RgbdCameraConfig cameraConfig(const CameraIntrinsics& k, const DepthNoiseConfig& noise) {
  RgbdCameraConfig c;
  c.intrinsics = k;
  c.noise = noise;
  c.max_range_m = 10.0;
  c.threads = 2;
  return c;
}

Eigen::Vector3d pixelDirection_C(const CameraIntrinsics& k, int u, int v) {
  return Eigen::Vector3d((u - k.cx_px) / k.fx_px, (v - k.cy_px) / k.fy_px, 1.0).normalized();
}

// Fronto-parallel wall z = distance for a camera at the origin looking along +z (identity pose).
Plane frontoWall(double distance, Albedo albedo = {180, 180, 180}) {
  return Plane{Eigen::Vector3d(0, 0, distance), Eigen::Vector3d(0, 0, -1), albedo};
}

// A floor (y = 1, below the identity camera), a box and a sphere; the sky above misses.
struct TestScene {
  Plane floor{Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0), {120, 140, 160}};
  Box box{Eigen::Vector3d(-0.55, 0.23, 3.1),
          Eigen::Vector3d(0.31, 0.42, 0.27),
          Eigen::Matrix3d::Identity(),
          {200, 40, 40}};
  Sphere sphere{Eigen::Vector3d(0.63, 0.04, 2.47), 0.41, {40, 200, 40}};
  AnalyticRayScene scene{2};
  std::int32_t floor_id = scene.add(floor);
  std::int32_t box_id = scene.add(box);
  std::int32_t sphere_id = scene.add(sphere, 0.2f);
};

std::optional<double> rayPlane(const Plane& p, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  const double nd = p.normal_W.dot(d);
  if (nd >= 0.0) return std::nullopt;  // seen from behind or parallel
  const double t = p.normal_W.dot(p.point_W - o) / nd;
  return t > 0.0 ? std::optional<double>(t) : std::nullopt;
}

std::optional<double> raySphere(const Sphere& s, const Eigen::Vector3d& o,
                                const Eigen::Vector3d& d) {
  const Eigen::Vector3d oc = o - s.centre_W;
  const double b = oc.dot(d);
  const double disc = b * b - (oc.squaredNorm() - s.radius_m * s.radius_m);
  if (disc < 0.0) return std::nullopt;
  const double t = -b - std::sqrt(disc);
  return t > 0.0 ? std::optional<double>(t) : std::nullopt;
}

std::optional<double> rayAxisBox(const Box& b, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  double near = -kInf, far = kInf;  // slab method
  for (int a = 0; a < 3; ++a) {
    const double lo = (b.centre_W[a] - b.half_extents_m[a] - o[a]) / d[a];
    const double hi = (b.centre_W[a] + b.half_extents_m[a] - o[a]) / d[a];
    near = std::max(near, std::min(lo, hi));
    far = std::min(far, std::max(lo, hi));
  }
  return (near <= far && near > 0.0) ? std::optional<double>(near) : std::nullopt;
}

struct Expected {
  double t = kInf;
  std::int32_t id = kNoHitObjectId;
};

Expected expectedHit(const TestScene& s, const Eigen::Vector3d& d) {
  const Eigen::Vector3d o = Eigen::Vector3d::Zero();
  Expected e;
  const auto consider = [&](std::optional<double> t, std::int32_t id) {
    if (t && *t < e.t) e = Expected{*t, id};
  };
  consider(rayPlane(s.floor, o, d), s.floor_id);
  consider(rayAxisBox(s.box, o, d), s.box_id);
  consider(raySphere(s.sphere, o, d), s.sphere_id);
  return e;
}

struct Stats {
  double mean = 0.0, stddev = 0.0;
  std::size_t count = 0;
};

Stats statsOf(const std::vector<double>& values) {
  Stats s;
  s.count = values.size();
  for (double v : values) s.mean += v;
  s.mean /= static_cast<double>(values.size());
  for (double v : values) s.stddev += (v - s.mean) * (v - s.mean);
  s.stddev = std::sqrt(s.stddev / static_cast<double>(values.size() - 1));
  return s;
}

// Share of hit pixels with measured depth 0.
double dropRate(const SimulatedFrame& f) {
  std::size_t hits = 0, dropped = 0;
  for (std::size_t i = 0; i < f.depth.depth_m.size(); ++i) {
    if (f.depth_true.depth_m[i] <= 0.0f) continue;
    ++hits;
    dropped += f.depth.depth_m[i] == 0.0f;
  }
  return static_cast<double>(dropped) / static_cast<double>(hits);
}

// Binomial rate within 3 sigma of p over n trials.
void expectRate(double rate, double p, std::size_t n) {
  EXPECT_NEAR(rate, p, 3.0 * std::sqrt(p * (1.0 - p) / static_cast<double>(n)) + 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Random numbers

TEST(SensorRng, SameSeedSameBitsAndSoundMoments) {
  Rng a(42), b(42), c(43);
  bool all_equal = true, any_different = false;
  for (int i = 0; i < 100; ++i) {
    const std::uint64_t x = a.next();
    all_equal &= x == b.next();
    any_different |= x != c.next();
  }
  EXPECT_TRUE(all_equal);
  EXPECT_TRUE(any_different);
  // Fixed bits on every machine: xoshiro256** seeded by SplitMix64(0).
  EXPECT_NE(Rng(0).next(), Rng::stream(0, 1).next());
  std::vector<double> uniforms, normals;
  Rng rng(7);
  for (int i = 0; i < 200000; ++i) {
    uniforms.push_back(rng.uniform());
    normals.push_back(rng.normal());
  }
  EXPECT_NEAR(statsOf(uniforms).mean, 0.5, 0.003);
  EXPECT_NEAR(statsOf(uniforms).stddev, std::sqrt(1.0 / 12.0), 0.003);
  EXPECT_NEAR(statsOf(normals).mean, 0.0, 0.007);
  EXPECT_NEAR(statsOf(normals).stddev, 1.0, 0.005);
}

// ---------------------------------------------------------------------------------------------
// RGB-D camera without noise: exact depth, object ids, shading

TEST(SensorRgbd, NoiseFreeDepthEqualsAnalyticDistance) {
  TestScene s;
  const CameraIntrinsics k = smallIntrinsics(96, 72, 60.0f);
  DepthNoiseConfig off = allEffectsOff();
  off.enabled = false;
  const RgbdCamera camera(cameraConfig(k, off));
  const SimulatedFrame f = camera.render(s.scene, Eigen::Isometry3d::Identity(), Lighting{}, 1);
  int sphere_pixels = 0, floor_pixels = 0;
  for (int v = 0; v < k.height_px; ++v) {
    for (int u = 0; u < k.width_px; ++u) {
      const Eigen::Vector3d d = pixelDirection_C(k, u, v);
      const Expected e = expectedHit(s, d);
      const double z = std::isfinite(e.t) ? e.t * d.z() : 0.0;
      const bool in_range = z >= 0.3 && z <= 10.0;
      ASSERT_NEAR(f.depth_true.at(u, v), z, 1e-4) << "pixel " << u << "," << v;
      ASSERT_NEAR(f.depth.at(u, v), in_range ? z : 0.0, 1e-4) << "pixel " << u << "," << v;
      sphere_pixels += e.id == s.sphere_id;
      floor_pixels += e.id == s.floor_id;
    }
  }
  EXPECT_GT(sphere_pixels, 200);
  EXPECT_GT(floor_pixels, 1000);
}

TEST(SensorRgbd, ObjectIdsRightOnEveryPixel) {
  TestScene s;
  EXPECT_EQ(s.floor_id, kStaticObjectId);
  EXPECT_EQ(s.box_id, 2);  // insertion index + 1
  EXPECT_EQ(s.sphere_id, 3);
  const CameraIntrinsics k = smallIntrinsics(160, 120, 100.0f);
  const RgbdCamera camera(cameraConfig(k, DepthNoiseConfig{}));
  const SimulatedFrame f = camera.render(s.scene, Eigen::Isometry3d::Identity(), Lighting{}, 3);
  std::set<std::int32_t> seen;
  for (int v = 0; v < k.height_px; ++v) {
    for (int u = 0; u < k.width_px; ++u) {
      const std::int32_t expected = expectedHit(s, pixelDirection_C(k, u, v)).id;
      ASSERT_EQ(f.object_ids.at(u, v), expected) << "pixel " << u << "," << v;
      seen.insert(expected);
    }
  }
  EXPECT_EQ(seen, (std::set<std::int32_t>{kNoHitObjectId, 0, 2, 3}));
}

TEST(SensorRgbd, ColourIsAlbedoTimesLambert) {
  AnalyticRayScene scene(1);
  scene.add(frontoWall(2.0, {200, 100, 50}));
  const CameraIntrinsics k = smallIntrinsics(16, 12, 20.0f);
  Lighting light;
  light.direction_W = Eigen::Vector3d(0, 0, -1);  // head-on onto the wall's normal
  light.intensity = 0.5;
  light.ambient = 0.25;
  const SimulatedFrame f = RgbdCamera(cameraConfig(k, DepthNoiseConfig{}))
                               .render(scene, Eigen::Isometry3d::Identity(), light, 0);
  for (std::size_t p = 0; p < f.color.rgb.size(); p += 3) {
    ASSERT_EQ(f.color.rgb[p], 150);  // 200 * 0.75
    ASSERT_EQ(f.color.rgb[p + 1], 75);
    ASSERT_EQ(f.color.rgb[p + 2], 38);  // 37.5 rounds up
  }
  const RgbdFrame frame = makeRgbdFrame(f, Eigen::Isometry3d::Identity(), 0.5, "0");
  EXPECT_NO_THROW(validateFrame(frame, k));
}

// ---------------------------------------------------------------------------------------------
// Noise model

TEST(SensorNoise, AxialStatisticsMatchModelAtSeveralDistances) {
  const CameraIntrinsics k = smallIntrinsics(160, 120, 525.0f);
  DepthNoiseConfig noise = allEffectsOff();
  noise.axial_noise = true;
  noise.quantize = true;
  const RgbdCamera camera(cameraConfig(k, noise));
  const double step = 1.0 / camera.config().depth_scale;
  for (double distance : {1.0, 2.0, 3.0, 4.0}) {
    AnalyticRayScene scene(2);
    scene.add(frontoWall(distance));
    const SimulatedFrame f = camera.render(scene, Eigen::Isometry3d::Identity(), Lighting{},
                                           static_cast<std::uint64_t>(distance * 10));
    std::vector<double> errors;
    for (std::size_t i = 0; i < f.depth.depth_m.size(); ++i) {
      errors.push_back(static_cast<double>(f.depth.depth_m[i]) - f.depth_true.depth_m[i]);
    }
    // Nguyen et al. 2012 at theta ~ 0, plus the uniform quantisation variance step^2 / 12.
    const double sigma = 0.0012 + 0.0019 * (distance - 0.4) * (distance - 0.4);
    const double expected = std::sqrt(sigma * sigma + step * step / 12.0);
    const Stats st = statsOf(errors);
    EXPECT_NEAR(st.mean, 0.0, 4.0 * expected / std::sqrt(static_cast<double>(st.count)))
        << distance << " m";
    EXPECT_NEAR(st.stddev / expected, 1.0, 0.1) << distance << " m";
    EXPECT_NEAR(st.stddev / expected, 1.0, 0.03) << distance << " m (tighter than asked)";
  }
}

TEST(SensorNoise, GrazingIncidenceDropsDepth) {
  DepthNoiseConfig noise = allEffectsOff();
  noise.grazing_dropout = true;
  EXPECT_DOUBLE_EQ(grazingDropProbability(noise, 69.0 * kPi / 180.0), 0.0);
  EXPECT_NEAR(grazingDropProbability(noise, 75.0 * kPi / 180.0), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(grazingDropProbability(noise, 81.0 * kPi / 180.0), 1.0);
  const CameraIntrinsics k = smallIntrinsics(64, 48, 525.0f);  // +-3.5 degrees
  const RgbdCamera camera(cameraConfig(k, noise));
  for (double tilt_deg : {85.0, 60.0}) {
    // Wall through (0, 0, 2) whose normal leans tilt_deg away from the optical axis.
    const double a = tilt_deg * kPi / 180.0;
    AnalyticRayScene scene(1);
    scene.add(Plane{Eigen::Vector3d(0, 0, 2), Eigen::Vector3d(0, -std::sin(a), -std::cos(a)), {}});
    const SimulatedFrame f = camera.render(scene, Eigen::Isometry3d::Identity(), Lighting{}, 5);
    const auto hits = std::count_if(f.depth_true.depth_m.begin(), f.depth_true.depth_m.end(),
                                    [](float z) { return z > 0.0f && z < 10.0f; });
    EXPECT_EQ(hits, k.width_px * k.height_px) << tilt_deg;
    EXPECT_DOUBLE_EQ(dropRate(f), tilt_deg > 80.0 ? 1.0 : 0.0) << tilt_deg;
  }
}

TEST(SensorNoise, DarkAndReflectiveDropoutRatesMatchProbability) {
  const CameraIntrinsics k = smallIntrinsics(80, 60, 100.0f);
  const std::size_t n = static_cast<std::size_t>(k.width_px) * k.height_px;
  DepthNoiseConfig noise = allEffectsOff();
  noise.dark_dropout = noise.reflective_dropout = true;
  noise.dark_dropout_probability = 0.35;
  const RgbdCamera camera(cameraConfig(k, noise));
  const auto rateFor = [&](Albedo albedo, float reflectivity, std::uint64_t seed) {
    AnalyticRayScene scene(1);
    scene.add(frontoWall(2.0, albedo), reflectivity);
    return dropRate(camera.render(scene, Eigen::Isometry3d::Identity(), Lighting{}, seed));
  };
  expectRate(rateFor({10, 10, 12}, 0.0f, 1), 0.35, n);    // dark
  expectRate(rateFor({200, 200, 200}, 0.9f, 2), 0.9, n);  // reflective (default 0.9)
  EXPECT_EQ(rateFor({200, 200, 200}, 0.5f, 3), 0.0);      // neither
  EXPECT_EQ(rateFor({30, 30, 30}, 0.0f, 4), 0.0);         // luminance 0.118 above 0.08
}

TEST(SensorNoise, OutOfRangeDepthIsZero) {
  const CameraIntrinsics k = smallIntrinsics(32, 24, 40.0f);
  RgbdCameraConfig config = cameraConfig(k, DepthNoiseConfig{});  // every effect on
  config.max_range_m = 5.0;
  config.noise.grazing_dropout = false;
  const RgbdCamera camera(config);
  for (double distance : {6.0, 0.2}) {
    AnalyticRayScene scene(1);
    scene.add(frontoWall(distance));
    const SimulatedFrame f = camera.render(scene, Eigen::Isometry3d::Identity(), Lighting{}, 9);
    for (std::size_t i = 0; i < f.depth.depth_m.size(); ++i) {
      ASSERT_GT(f.depth_true.depth_m[i], 0.0f);
      ASSERT_EQ(f.depth.depth_m[i], 0.0f) << distance;
    }
  }
}

TEST(SensorNoise, FlyingPixelsLieBetweenTheSurfacesAtEdges) {
  AnalyticRayScene scene(1);
  scene.add(frontoWall(3.0));
  scene.add(Sphere{Eigen::Vector3d(0.1, 0.05, 1.5), 0.4, {}});
  const CameraIntrinsics k = smallIntrinsics(120, 90, 110.0f);
  DepthNoiseConfig noise = allEffectsOff();
  noise.flying_pixels = true;
  for (double probability : {1.0, 0.3}) {
    noise.flying_pixel_probability = probability;
    const SimulatedFrame f = RgbdCamera(cameraConfig(k, noise))
                                 .render(scene, Eigen::Isometry3d::Identity(), Lighting{}, 11);
    std::size_t edge = 0, flew = 0;
    for (int v = 1; v + 1 < k.height_px; ++v) {
      for (int u = 1; u + 1 < k.width_px; ++u) {
        const float z = f.depth_true.at(u, v), measured = f.depth.at(u, v);
        float lo = z, hi = z, jump = 0.0f;  // jump: largest |neighbour - z|
        for (const auto& [du, dv] : {std::pair{-1, 0}, {1, 0}, {0, -1}, {0, 1}}) {
          const float other = f.depth_true.at(u + du, v + dv);
          lo = std::min(lo, other);
          hi = std::max(hi, other);
          jump = std::max(jump, std::abs(other - z));
        }
        if (jump <= noise.flying_min_jump_m) {
          ASSERT_EQ(measured, z) << "smooth pixel changed at " << u << "," << v;
          continue;
        }
        ++edge;
        ASSERT_GE(measured, lo);
        ASSERT_LE(measured, hi);
        flew += measured != z;
      }
    }
    ASSERT_GT(edge, 150u);
    expectRate(static_cast<double>(flew) / edge, probability, edge);
  }
}

TEST(SensorNoise, QuantisationRoundsAndSaturates) {
  EXPECT_FLOAT_EQ(quantizeDepth(1.00009f, 5000.0), 1.0f);
  EXPECT_FLOAT_EQ(quantizeDepth(1.00011f, 5000.0), 1.0002f);
  EXPECT_FLOAT_EQ(quantizeDepth(20.0f, 5000.0), 65535.0f / 5000.0f);
  EXPECT_EQ(quantizeDepth(0.0f, 5000.0), 0.0f);
}

TEST(SensorNoise, BadConfigNamesTheField) {
  RgbdCameraConfig config;
  config.noise.dark_dropout_probability = 1.5;
  try {
    RgbdCamera camera(config);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("dark_dropout_probability"), std::string::npos);
  }
}

// ---------------------------------------------------------------------------------------------
// Determinism

TEST(SensorDeterminism, SameSeedSameBytesAnyThreadCountNewSeedNewNoise) {
  TestScene s;
  const CameraIntrinsics k = smallIntrinsics(64, 48, 50.0f);
  const Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  RgbdCameraConfig config = cameraConfig(k, DepthNoiseConfig{});
  std::vector<SimulatedFrame> frames;
  for (int threads : {1, 2, 3}) {
    config.threads = threads;
    frames.push_back(RgbdCamera(config).render(s.scene, pose, Lighting{}, 1234));
  }
  const SimulatedFrame other = RgbdCamera(config).render(s.scene, pose, Lighting{}, 1235);
  const auto sameBytes = [](const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
  };
  for (const SimulatedFrame& f : frames) {
    EXPECT_TRUE(sameBytes(f.depth.depth_m, frames[0].depth.depth_m));
    EXPECT_TRUE(sameBytes(f.color.rgb, frames[0].color.rgb));
    EXPECT_TRUE(sameBytes(f.object_ids.ids, frames[0].object_ids.ids));
  }
  EXPECT_FALSE(sameBytes(other.depth.depth_m, frames[0].depth.depth_m));
  EXPECT_TRUE(sameBytes(other.depth_true.depth_m, frames[0].depth_true.depth_m));

  GreyCameraConfig grey;
  grey.intrinsics = k;
  grey.baseline_m = 0.1;
  const GreyFrame g1 = GreyCamera(grey).render(s.scene, pose, Lighting{}, 5);
  grey.threads = 1;
  const GreyFrame g2 = GreyCamera(grey).render(s.scene, pose, Lighting{}, 5);
  const GreyFrame g3 = GreyCamera(grey).render(s.scene, pose, Lighting{}, 6);
  EXPECT_TRUE(sameBytes(g1.eyes[1].pixels, g2.eyes[1].pixels));
  EXPECT_FALSE(sameBytes(g1.eyes[1].pixels, g3.eyes[1].pixels));
}

// ---------------------------------------------------------------------------------------------
// Grey camera

TEST(SensorGrey, StereoPairShowsTexturedWallAtTheRightDisparity) {
  AnalyticRayScene scene(1);
  scene.add(frontoWall(2.0));
  GreyCameraConfig config;
  config.intrinsics = smallIntrinsics(120, 80, 100.0f);
  config.baseline_m = 0.1;  // disparity f b / z = 5 px
  config.pixel_noise_sigma = 0.0;
  Lighting light;
  light.direction_W = Eigen::Vector3d(0, 0, -1);  // head-on: full albedo
  const GreyFrame f = GreyCamera(config).render(scene, Eigen::Isometry3d::Identity(), light, 0);
  ASSERT_EQ(f.eyes.size(), 2u);
  EXPECT_NEAR((f.T_W_eye[1].translation() - Eigen::Vector3d(0.1, 0, 0)).norm(), 0.0, 1e-15);
  int equal = 0, compared = 0, edges = 0;
  std::set<int> levels;
  for (int v = 0; v < 80; ++v) {
    for (int u = 5; u < 120; ++u) {
      ++compared;
      equal += f.eyes[0].at(u, v) == f.eyes[1].at(u - 5, v);  // x_R = x_L - b
      levels.insert(f.eyes[0].at(u, v));
      edges += std::abs(f.eyes[0].at(u, v) - f.eyes[0].at(u - 1, v)) > 20;
    }
  }
  EXPECT_GT(equal, 0.99 * compared);
  EXPECT_GT(levels.size(), 30u);  // non-repeating texture
  EXPECT_GT(edges, 200);          // sharp cell borders for corner detectors
}

// ---------------------------------------------------------------------------------------------
// Trajectories

std::vector<Waypoint> roomLoop() {
  return {{{0.0, -1.5, 1.4}, {0.0, 1.0, 0.8}},  {{0.8, -1.0, 1.5}, {-0.5, 1.0, 0.6}},
          {{1.3, 0.0, 1.3}, {-1.0, 0.2, 0.7}},  {{0.7, 1.1, 1.6}, {-0.3, -0.8, 0.9}},
          {{-0.6, 1.2, 1.4}, {0.5, -1.0, 0.5}}, {{-1.2, 0.1, 1.2}, {1.0, 0.0, 0.8}}};
}

TEST(SensorTrajectory, QuinticSplineInterpolatesAndStartsAtRest) {
  const auto& M = QuinticBSpline::basisMatrix();
  const double row0[6] = {1, 26, 66, 26, 1, 0};
  for (int j = 0; j < 6; ++j) EXPECT_NEAR(M(0, j), row0[j] / 120.0, 1e-15);
  for (int i = 1; i < 6; ++i) EXPECT_NEAR(M.row(i).sum(), 0.0, 1e-12);  // partition of unity
  std::vector<Eigen::Vector3d> points;
  for (const Waypoint& w : roomLoop()) points.push_back(w.position_W);
  const QuinticBSpline spline(points, 1.7);
  for (std::size_t k = 0; k < points.size(); ++k) {
    EXPECT_NEAR((spline.evaluate(1.7 * k) - points[k]).norm(), 0.0, 1e-12);
  }
  for (double t : {0.0, spline.duration_s()}) {
    EXPECT_NEAR(spline.evaluate(t, 1).norm(), 0.0, 1e-12);
    EXPECT_NEAR(spline.evaluate(t, 2).norm(), 0.0, 1e-12);
  }
}

TEST(SensorTrajectory, DerivativesMatchFiniteDifferences) {
  const Trajectory trajectory(roomLoop(), TrajectoryConfig{}, 3);
  ASSERT_GT(trajectory.duration_s(), 10.0);
  const double h = 1e-4;
  for (double t = 0.3; t < trajectory.duration_s() - 0.3; t += 0.37) {
    const TrajectoryState s = trajectory.state(t);
    const TrajectoryState a = trajectory.state(t - h), b = trajectory.state(t + h);
    const Eigen::Vector3d v_fd = (b.T_W_C.translation() - a.T_W_C.translation()) / (2 * h);
    EXPECT_NEAR((v_fd - s.velocity_W).norm(), 0.0, 1e-6) << t;
    EXPECT_NEAR(((b.velocity_W - a.velocity_W) / (2 * h) - s.acceleration_W).norm(), 0.0, 1e-6);
    // R(t + h) = R(t - h) Exp(2 h w(t)) + O(h^3).
    const Eigen::AngleAxisd delta(a.T_W_C.linear().transpose() * b.T_W_C.linear());
    EXPECT_NEAR((delta.angle() * delta.axis() / (2 * h) - s.angular_velocity_C).norm(), 0.0, 1e-6);
    const Eigen::Vector3d alpha_fd = (b.angular_velocity_C - a.angular_velocity_C) / (2 * h);
    EXPECT_NEAR((alpha_fd - s.angular_acceleration_C).norm(), 0.0, 1e-4) << t;
    EXPECT_LT(s.velocity_W.norm(), 1.5);  // hand-held pace
  }
  EXPECT_EQ(trajectory.sample(30.0).size(), trajectory.sampleTimes(30.0).size());
  EXPECT_THROW(Trajectory({roomLoop()[0]}, TrajectoryConfig{}, 0), InputError);
  EXPECT_THROW(Trajectory({{{0, 0, 1}, {0, 0, 3}}, {{1, 0, 1}, {0, 0, 0}}}, TrajectoryConfig{}, 0),
               InputError);  // looks straight up
}

// ---------------------------------------------------------------------------------------------
// IMU

// Integrates noise-free samples with RK4 (dt = sample spacing); the rates at the step midpoint come
// from cubic Lagrange interpolation over four consecutive samples. Returns the final T_W_B.
Eigen::Isometry3d integrateImu(const std::vector<ImuSample>& samples, const Eigen::Isometry3d& T0,
                               Eigen::Vector3d v, double gravity) {
  const auto at = [&](std::size_t k, double s) {  // rates at t_k + s dt, s in [0, 1]
    const std::size_t i = std::clamp<std::size_t>(k, 1, samples.size() - 3) - 1;  // window start
    const double x = static_cast<double>(k - i) + s;                              // in [0, 3]
    Eigen::Matrix<double, 6, 1> r = Eigen::Matrix<double, 6, 1>::Zero();
    for (int j = 0; j < 4; ++j) {
      double w = 1.0;
      for (int m = 0; m < 4; ++m) {
        if (m != j) w *= (x - m) / static_cast<double>(j - m);
      }
      r.head<3>() += w * samples[i + j].gyro_rad_s;
      r.tail<3>() += w * samples[i + j].accel_mps2;
    }
    return r;
  };
  struct State {
    Eigen::Quaterniond q;
    Eigen::Vector3d v, p;
  };
  struct Rate {
    Eigen::Vector4d dq;
    Eigen::Vector3d dv, dp;
  };
  const Eigen::Vector3d g(0, 0, -gravity);
  const auto f = [&](const State& x, const Eigen::Matrix<double, 6, 1>& r) {
    const Eigen::Quaterniond w(0.0, r(0), r(1), r(2));
    // dq/dt = q (x) (0, w) / 2, dv/dt = R f + g, dp/dt = v.
    return Rate{0.5 * (x.q * w).coeffs(), x.q.normalized() * Eigen::Vector3d(r.tail<3>()) + g, x.v};
  };
  const auto step = [](const State& x, const Rate& k, double dt) {
    return State{Eigen::Quaterniond(Eigen::Vector4d(x.q.coeffs() + dt * k.dq)), x.v + dt * k.dv,
                 x.p + dt * k.dp};
  };
  State x{Eigen::Quaterniond(T0.linear()), v, T0.translation()};
  for (std::size_t k = 0; k + 1 < samples.size(); ++k) {
    const double dt = samples[k + 1].t_s - samples[k].t_s;
    const Rate k1 = f(x, at(k, 0.0));
    const Rate k2 = f(step(x, k1, dt / 2), at(k, 0.5));
    const Rate k3 = f(step(x, k2, dt / 2), at(k, 0.5));
    const Rate k4 = f(step(x, k3, dt), at(k, 1.0));
    x.q.coeffs() += dt / 6 * (k1.dq + 2 * k2.dq + 2 * k3.dq + k4.dq);
    x.q.normalize();
    x.v += dt / 6 * (k1.dv + 2 * k2.dv + 2 * k3.dv + k4.dv);
    x.p += dt / 6 * (k1.dp + 2 * k2.dp + 2 * k3.dp + k4.dp);
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = x.q.toRotationMatrix();
  T.translation() = x.p;
  return T;
}

Trajectory tenSecondTrajectory() {
  std::vector<Waypoint> w = roomLoop();
  w.resize(4);
  TrajectoryConfig config;
  config.mean_speed_mps = 0.33;  // three segments of ~3.4 s
  return Trajectory(w, config, 8);
}

TEST(SensorImu, IntegratingNoiseFreeSamplesReproducesTheTrajectory) {
  const Trajectory trajectory = tenSecondTrajectory();
  ASSERT_GE(trajectory.duration_s(), 10.0);
  ASSERT_LT(trajectory.duration_s(), 11.0);
  for (bool lever_arm : {false, true}) {
    ImuConfig config;
    config.noise = false;
    if (lever_arm) {
      config.T_C_B.linear() =
          Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).matrix();
      config.T_C_B.translation() = Eigen::Vector3d(0.05, -0.03, 0.02);
    }
    const std::vector<ImuSample> samples = simulateImu(trajectory, config, 1);
    ASSERT_EQ(samples.size(), trajectory.sampleTimes(200.0).size());
    const TrajectoryState s0 = trajectory.state(0.0);
    // Body velocity: v_C + R_W_C (w_C x t_C_B).
    const Eigen::Vector3d v0 =
        s0.velocity_W + s0.T_W_C.linear() * s0.angular_velocity_C.cross(config.T_C_B.translation());
    const Eigen::Isometry3d T_end =
        integrateImu(samples, s0.T_W_C * config.T_C_B, v0, config.gravity_mps2);
    const Eigen::Isometry3d truth = trajectory.pose(samples.back().t_s) * config.T_C_B;
    EXPECT_LT((T_end.translation() - truth.translation()).norm(), 1e-3) << lever_arm;
    EXPECT_LT(Eigen::AngleAxisd(T_end.linear().transpose() * truth.linear()).angle(), 1e-5);
  }
}

TEST(SensorImu, NoiseAndBiasWalkFollowTheDiscreteModel) {
  const Trajectory trajectory = tenSecondTrajectory();
  ImuConfig config;
  config.gyro_random_walk = config.accel_random_walk = 0.0;
  config.initial_gyro_bias = Eigen::Vector3d(0.01, -0.02, 0.03);
  const std::vector<ImuSample> noisy = simulateImu(trajectory, config, 21);
  config.noise = false;
  const std::vector<ImuSample> exact = simulateImu(trajectory, config, 21);
  std::vector<double> gyro_errors, accel_errors;
  for (std::size_t k = 0; k < noisy.size(); ++k) {
    for (int a = 0; a < 3; ++a) {
      gyro_errors.push_back(noisy[k].gyro_rad_s[a] - exact[k].gyro_rad_s[a]);
      accel_errors.push_back(noisy[k].accel_mps2[a] - exact[k].accel_mps2[a]);
    }
  }
  const double sqrt_dt = std::sqrt(1.0 / config.rate_hz);
  EXPECT_NEAR(statsOf(gyro_errors).stddev / (ImuConfig{}.gyro_noise_density / sqrt_dt), 1.0, 0.05);
  EXPECT_NEAR(statsOf(accel_errors).stddev / (ImuConfig{}.accel_noise_density / sqrt_dt), 1.0,
              0.05);
  EXPECT_NEAR((exact[7].gyro_bias - config.initial_gyro_bias).norm(), 0.0, 1e-15);

  ImuConfig walk;
  walk.gyro_noise_density = walk.accel_noise_density = 0.0;
  const std::vector<ImuSample> walked = simulateImu(trajectory, walk, 22);
  std::vector<double> steps;
  for (std::size_t k = 1; k < walked.size(); ++k) {
    for (int a = 0; a < 3; ++a)
      steps.push_back(walked[k].accel_bias[a] - walked[k - 1].accel_bias[a]);
  }
  EXPECT_NEAR(statsOf(steps).stddev / (walk.accel_random_walk * sqrt_dt), 1.0, 0.05);
}

TEST(SensorImu, EurocCsvHeaderAndRows) {
  const Trajectory trajectory = tenSecondTrajectory();
  ImuConfig config;
  config.start_time_ns = 1403636579758555392LL;  // an EuRoC-like epoch
  const std::vector<ImuSample> samples = simulateImu(trajectory, config, 3);
  const std::string path = (std::filesystem::temp_directory_path() /
                            ("strata_imu_" + std::to_string(::getpid()) + ".csv"))
                               .string();
  writeImuCsv(path, samples);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line,
            "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
            "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]");
  std::size_t rows = 0;
  while (std::getline(in, line)) {
    if (rows == 1) {
      EXPECT_EQ(line.substr(0, line.find(',')), "1403636579763555392");  // +5 ms
    }
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 6);
    ++rows;
  }
  EXPECT_EQ(rows, samples.size());
  std::filesystem::remove(path);
}

// ---------------------------------------------------------------------------------------------
// Odometry drift

TEST(SensorDrift, RandomWalkGrowsWithDistanceAndKeepsRollPitch) {
  std::vector<Eigen::Isometry3d> truth;
  for (int k = 0; k <= 100; ++k) {  // 10 m straight line, 0.1 m steps
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(0.1 * k, 0.0, 1.0);
    truth.push_back(T);
  }
  const DriftConfig config;
  EXPECT_EQ(addOdometryDrift(truth, DriftConfig{0.0, 0.0}, 1).back().matrix(),
            truth.back().matrix());
  std::vector<double> z_errors, yaw_errors;
  for (std::uint64_t seed = 0; seed < 400; ++seed) {
    const std::vector<Eigen::Isometry3d> drifted = addOdometryDrift(truth, config, seed);
    ASSERT_EQ(drifted.front().matrix(), truth.front().matrix());
    const Eigen::Matrix3d dR = drifted.back().linear() * truth.back().linear().transpose();
    ASSERT_NEAR(dR(2, 2), 1.0, 1e-12);  // pure yaw
    yaw_errors.push_back(std::atan2(dR(1, 0), dR(0, 0)));
    z_errors.push_back(drifted.back().translation().z() - 1.0);
  }
  // After L = 10 m: sigma = sigma_per_sqrt_m * sqrt(L); 400 draws estimate it to ~3.5 %.
  EXPECT_NEAR(statsOf(z_errors).stddev / (config.translation_sigma_m_per_sqrt_m * std::sqrt(10.0)),
              1.0, 0.15);
  EXPECT_NEAR(statsOf(yaw_errors).stddev / (config.yaw_sigma_rad_per_sqrt_m * std::sqrt(10.0)), 1.0,
              0.15);
  EXPECT_EQ(addOdometryDrift(truth, config, 5).back().matrix(),
            addOdometryDrift(truth, config, 5).back().matrix());
}

}  // namespace
}  // namespace strata::sim

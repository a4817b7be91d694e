// Simulated sensors: RGB-D camera (exact depth, object ids, noise model), grey camera and the
// deterministic random numbers behind them (motion models: test_sensor_motion.cpp).
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

#include "strata/core/error.h"
#include "sensor_stats.h"
#include "strata/sim/sensors/analytic_ray_scene.h"
#include "strata/sim/sensors/grey_camera.h"
#include "strata/sim/sensors/imu.h"
#include "strata/sim/sensors/odometry_drift.h"
#include "strata/sim/sensors/quintic_spline.h"
#include "strata/sim/sensors/rgbd_camera.h"
#include "strata/sim/rng.h"
#include "strata/sim/sensors/camera_path.h"

namespace strata::sim {
namespace {

using test::Stats;
using test::statsOf;

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

TEST(SensorRgbd, ColourTextureIsTheWorldTextureTimesTheFlatColourAndLeavesDepthAlone) {
  AnalyticRayScene scene(1);
  scene.add(frontoWall(2.0, {200, 100, 50}));
  const CameraIntrinsics k = smallIntrinsics(64, 48, 40.0f);
  Lighting light;
  light.direction_W = Eigen::Vector3d(0, 0, -1);
  RgbdCameraConfig flat_config = cameraConfig(k, DepthNoiseConfig{});
  RgbdCameraConfig textured_config = flat_config;
  textured_config.color_texture = WorldTextureConfig{};
  const SimulatedFrame flat =
      RgbdCamera(flat_config).render(scene, Eigen::Isometry3d::Identity(), light, 0);
  const SimulatedFrame textured =
      RgbdCamera(textured_config).render(scene, Eigen::Isometry3d::Identity(), light, 0);
  EXPECT_EQ(flat.depth.depth_m, textured.depth.depth_m);
  std::set<int> levels;
  for (std::size_t p = 0; p < flat.color.rgb.size(); p += 3) {
    ASSERT_LE(textured.color.rgb[p], flat.color.rgb[p]);  // the factor is at most 1
    levels.insert(textured.color.rgb[p]);
  }
  EXPECT_GT(levels.size(), 8u);  // cells of many grey levels, not one flat colour
  WorldTextureConfig bad;
  bad.contrast = 2.0;
  textured_config.color_texture = bad;
  EXPECT_THROW(RgbdCamera{textured_config}, InputError);
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

}  // namespace
}  // namespace strata::sim

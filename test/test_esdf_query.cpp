// Host ESDF queries (EsdfQuery) on an analytic sphere ESDF: exact distances, radial gradients,
// sphere / segment / path checks near and far from the obstacle, unknown space, bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <thread>

#include "esdf_sphere_scene.h"
#include "strata/esdf/esdf_query.h"

namespace strata {
namespace {

using test::SphereEsdfScene;
constexpr float kVoxel = SphereEsdfScene::kVoxelSizeM;
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

/// Random points inside the cube of blocks (x below the unknown slab unless `anywhere`).
std::vector<Eigen::Vector3f> randomPoints(std::size_t count, std::uint32_t seed, bool anywhere) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.2f, anywhere ? 1.2f : 0.65f);
  std::uniform_real_distribution<float> w(-1.2f, 1.2f);
  std::vector<Eigen::Vector3f> points;
  for (std::size_t i = 0; i < count; ++i) {
    // NOTE: one draw per statement, z first: C++ leaves the order of f(u(rng), w(rng)) open (gcc
    // draws the last argument first, clang the first), and the points must not depend on it.
    const float z = w(rng);
    const float y = w(rng);
    const float x = u(rng);
    points.emplace_back(x, y, z);
  }
  return points;
}

/// Brute force over voxel centres within R of c: any unknown / unallocated one?
bool unknownWithin(const EsdfMap& map, const Eigen::Vector3f& c, float r) {
  const int reach = static_cast<int>(std::ceil(r / kVoxel)) + 1;
  const GlobalVoxelIndex v0 = (c / kVoxel).array().floor().cast<int>().matrix();
  for (int z = -reach; z <= reach; ++z) {
    for (int y = -reach; y <= reach; ++y) {
      for (int x = -reach; x <= reach; ++x) {
        const GlobalVoxelIndex v = v0 + Eigen::Vector3i(x, y, z);
        if ((voxelCenter(v, kVoxel) - c).norm() > r) continue;
        const EsdfVoxel* voxel = map.findVoxel(v);
        if (voxel == nullptr || !esdfObserved(*voxel)) return true;
      }
    }
  }
  return false;
}

TEST(EsdfQuery, DistanceIsExactAtVoxelCentres) {
  const SphereEsdfScene& scene = test::sphereEsdfScene();
  const EsdfQuery query(scene.map);
  std::vector<Eigen::Vector3f> centres;
  for (const Eigen::Vector3f& p : randomPoints(5000, 1, false)) {
    centres.push_back(voxelCenter((p / kVoxel).array().floor().cast<int>().matrix(), kVoxel));
  }
  const std::vector<EsdfSample> samples = query.sample(centres);
  for (std::size_t i = 0; i < centres.size(); ++i) {
    ASSERT_EQ(samples[i].status, EsdfStatus::kKnown) << centres[i].transpose();
    const float expected = std::fmin(scene.nearestSiteDistance(centres[i]), 1.0f);
    const float sign = scene.surfaceDistance(centres[i]) < 0.0f ? -1.0f : 1.0f;
    EXPECT_NEAR(samples[i].distance_m, sign * expected, 1e-5f) << centres[i].transpose();
    // Sites sit within half a voxel of the surface: the ESDF is the sphere's SDF within ~1 voxel.
    if (expected < 1.0f) {
      EXPECT_NEAR(samples[i].distance_m, scene.surfaceDistance(centres[i]), kVoxel);
    }
  }
}

TEST(EsdfQuery, GradientPointsRadiallyAwayFromTheSphere) {
  const SphereEsdfScene& scene = test::sphereEsdfScene();
  const EsdfQuery query(scene.map);
  std::size_t checked = 0;
  float mean_cosine = 0.0f;
  std::size_t off_by_12_degrees = 0;
  for (const Eigen::Vector3f& p : randomPoints(5000, 2, false)) {
    const float d = scene.surfaceDistance(p);
    // Away from the shell (kinks), the sphere's centre, the 1 m cap and the map's border.
    if (!((d > 3 * kVoxel && d < 0.8f) || (d < -3 * kVoxel && d > -0.35f))) continue;
    if (p.cwiseAbs().maxCoeff() > 1.15f) continue;
    const EsdfSample s = query.sample(p);
    ASSERT_TRUE(s.interpolated) << p.transpose();
    const Eigen::Vector3f radial = (p - scene.centre_W).normalized();
    const float cosine = s.gradient.normalized().dot(radial);
    // The sites are voxel centres, not the smooth sphere: a few degrees off radial, rarely ~20.
    EXPECT_GT(cosine, std::cos(0.45f)) << p.transpose();
    off_by_12_degrees += cosine < std::cos(0.21f) ? 1 : 0;
    EXPECT_NEAR(s.gradient.norm(), 1.0f, 0.2f) << p.transpose();
    mean_cosine += cosine;
    ++checked;
  }
  ASSERT_GT(checked, 1000u);
  EXPECT_GT(mean_cosine / static_cast<float>(checked), 0.995f);
  EXPECT_LT(off_by_12_degrees, checked * 3 / 100);
}

TEST(EsdfQuery, SpheresNearAndFarFromTheObstacle) {
  const SphereEsdfScene& scene = test::sphereEsdfScene();
  const EsdfQuery query(scene.map);
  const Eigen::Vector3f far = scene.centre_W + Eigen::Vector3f(-0.9f, 0.0f, 0.0f);  // 0.4 m out
  for (UnknownPolicy policy : {UnknownPolicy::kOccupied, UnknownPolicy::kFree}) {
    EXPECT_TRUE(query.isSphereFree(far, 0.2f, 0.1f, policy));
    EXPECT_FALSE(query.isSphereFree(far, 0.3f, 0.15f, policy));            // margin makes it touch
    EXPECT_FALSE(query.isSphereFree(scene.centre_W, 0.0f, 0.0f, policy));  // inside
    EXPECT_FALSE(query.isSphereFree(far, 1.5f, 0.0f, policy));             // beyond max distance
  }
  // Every sphere reported free holds no site within its radius (brute force).
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> radius(0.0f, 0.4f);
  const std::vector<Eigen::Vector3f> centres = randomPoints(3000, 4, true);
  std::vector<float> radii;
  for (std::size_t i = 0; i < centres.size(); ++i) radii.push_back(radius(rng));
  std::size_t free_count = 0;
  for (std::size_t i = 0; i < centres.size(); ++i) {
    for (UnknownPolicy policy : {UnknownPolicy::kOccupied, UnknownPolicy::kFree}) {
      if (!query.isSphereFree(centres[i], radii[i], 0.0f, policy)) continue;
      ++free_count;
      EXPECT_GT(scene.nearestSiteDistance(centres[i]), radii[i]) << centres[i].transpose();
      EXPECT_GT(scene.surfaceDistance(centres[i]), 0.0f) << centres[i].transpose();
    }
  }
  EXPECT_GT(free_count, 1000u);
}

TEST(EsdfQuery, UnknownIsNeverFreeWhenTreatedAsOccupied) {
  const SphereEsdfScene& scene = test::sphereEsdfScene();
  const EsdfQuery query(scene.map);
  const Eigen::Vector3f in_slab(0.75f, -0.9f, -0.9f);   // allocated, never observed
  const Eigen::Vector3f in_missing(1.0f, 1.0f, 1.0f);   // unallocated block
  const Eigen::Vector3f beyond(5.0f, 0.0f, 0.0f);       // no block at all
  const Eigen::Vector3f near_slab(0.6f, -0.9f, -0.9f);  // known, 0.1 m from the slab
  EXPECT_EQ(query.status(in_slab), EsdfStatus::kUnknown);
  EXPECT_EQ(query.status(in_missing), EsdfStatus::kOutside);
  EXPECT_EQ(query.status(beyond), EsdfStatus::kOutside);
  EXPECT_EQ(query.status(near_slab), EsdfStatus::kKnown);
  for (const Eigen::Vector3f& p : {in_slab, in_missing, beyond}) {
    EXPECT_FALSE(query.isSphereFree(p, 0.0f, 0.0f, UnknownPolicy::kOccupied)) << p.transpose();
    EXPECT_TRUE(query.isSphereFree(p, 0.1f, 0.0f, UnknownPolicy::kFree)) << p.transpose();
  }
  EXPECT_FALSE(query.isSphereFree(near_slab, 0.2f, 0.0f, UnknownPolicy::kOccupied));
  EXPECT_TRUE(query.isSphereFree(near_slab, 0.2f, 0.0f, UnknownPolicy::kFree));
  EXPECT_FALSE(query.isSegmentFree(near_slab, beyond, 0.0f, UnknownPolicy::kOccupied));
  // Random spheres: free under kOccupied means no unknown voxel centre inside (brute force).
  std::size_t free_count = 0;
  for (const Eigen::Vector3f& c : randomPoints(3000, 5, true)) {
    if (!query.isSphereFree(c, 0.15f, 0.0f, UnknownPolicy::kOccupied)) continue;
    ++free_count;
    EXPECT_FALSE(unknownWithin(scene.map, c, 0.15f)) << c.transpose();
  }
  EXPECT_GT(free_count, 300u);
}

TEST(EsdfQuery, SegmentsAndPaths) {
  const SphereEsdfScene& scene = test::sphereEsdfScene();
  const EsdfQuery query(scene.map);
  const Eigen::Vector3f o = scene.centre_W;
  const Eigen::Vector3f a = o + Eigen::Vector3f(-0.8f, -0.8f, 0.0f);
  const Eigen::Vector3f b = o + Eigen::Vector3f(-0.8f, 0.8f, 0.0f);  // 0.3 m clear of the sphere
  const Eigen::Vector3f c = o + Eigen::Vector3f(0.5f, 0.85f, 0.0f);
  const Eigen::Vector3f through = o + Eigen::Vector3f(0.65f, -0.8f, 0.0f);
  EXPECT_TRUE(query.isSegmentFree(a, b, 0.2f));
  EXPECT_FALSE(query.isSegmentFree(a, b, 0.35f));
  // Both ends are free but the middle crosses the sphere: the samples catch it.
  EXPECT_TRUE(query.isSphereFree(a, 0.1f, 0.0f) && query.isSphereFree(c, 0.1f, 0.0f));
  EXPECT_FALSE(query.isSegmentFree(a, c, 0.1f));
  EXPECT_TRUE(query.isPathFree({a, b, c}, 0.1f));
  EXPECT_FALSE(query.isPathFree({a, b, c, through}, 0.1f));
  EXPECT_TRUE(query.isPathFree({}, 0.1f));
  EXPECT_EQ(query.isPathFree({a}, 0.1f), query.isSphereFree(a, 0.1f, 0.0f));
  // Batch: a segment reported free keeps its radius from every site (brute force on samples).
  const std::vector<Eigen::Vector3f> ends = randomPoints(400, 6, false);
  std::vector<EsdfSegment> segments;
  for (std::size_t i = 0; i + 1 < ends.size(); i += 2) segments.push_back({ends[i], ends[i + 1]});
  const std::vector<std::uint8_t> free = query.isSegmentFree(segments, 0.05f);
  for (std::size_t i = 0; i < segments.size(); ++i) {
    EXPECT_EQ(free[i] != 0, query.isSegmentFree(segments[i].a_W, segments[i].b_W, 0.05f));
    if (!free[i]) continue;
    for (float t = 0.0f; t <= 1.0f; t += 0.01f) {
      const Eigen::Vector3f p = segments[i].a_W + t * (segments[i].b_W - segments[i].a_W);
      EXPECT_GT(scene.nearestSiteDistance(p), 0.05f) << p.transpose();
    }
  }
}

TEST(EsdfQuery, BadInputGivesDefinedAnswers) {
  const SphereEsdfScene& scene = test::sphereEsdfScene();
  const EsdfMap empty;
  const Eigen::Vector3f nan_point(kNaN, 0.0f, 0.0f);
  // NaN in y or z: Eigen's maxCoeff may pass over it (UndefinedBehaviorSanitizer caught the cast
  // of such a point to a voxel index).
  const Eigen::Vector3f nan_y(0.0f, kNaN, 0.0f);
  const Eigen::Vector3f nan_z(0.0f, 0.0f, kNaN);
  const Eigen::Vector3f inf_point(std::numeric_limits<float>::infinity(), 0.0f, 0.0f);
  const Eigen::Vector3f huge_point(1e20f, -1e20f, 0.0f);
  const Eigen::Vector3f ok(-0.9f, 0.0f, 0.0f);
  for (const EsdfMap* map : {&scene.map, &empty}) {
    const EsdfQuery query(*map);
    for (const Eigen::Vector3f& p : {nan_point, nan_y, nan_z, inf_point, huge_point}) {
      const EsdfSample s = query.sample(p);
      EXPECT_EQ(s.status, EsdfStatus::kOutside);
      EXPECT_EQ(s.distance_m, 0.0f);
      EXPECT_TRUE(s.gradient.isZero());
      EXPECT_FALSE(query.isSphereFree(p, 0.1f, 0.0f, UnknownPolicy::kOccupied));
      EXPECT_FALSE(query.isSphereFree(p, 0.1f, 0.0f, UnknownPolicy::kFree));
      EXPECT_FALSE(query.isSegmentFree(ok, p, 0.1f, UnknownPolicy::kFree));
      EXPECT_FALSE(query.isPathFree({ok, ok, p}, 0.1f, UnknownPolicy::kFree));
    }
    EXPECT_FALSE(query.isSphereFree(ok, kNaN, 0.0f, UnknownPolicy::kFree));
    EXPECT_FALSE(query.isSphereFree(ok, -0.1f, 0.0f, UnknownPolicy::kFree));
    EXPECT_FALSE(query.isSegmentFree(ok, ok, kNaN, UnknownPolicy::kFree));
    EXPECT_TRUE(query.sample(std::vector<Eigen::Vector3f>{}).empty());
  }
  const EsdfQuery on_empty(empty);
  EXPECT_EQ(on_empty.sample(ok).status, EsdfStatus::kOutside);
  EXPECT_FALSE(on_empty.isSphereFree(ok, 0.1f, 0.0f, UnknownPolicy::kOccupied));
  EXPECT_TRUE(on_empty.isSphereFree(ok, 0.1f, 0.0f, UnknownPolicy::kFree));  // nothing known
}

TEST(EsdfQuery, BatchesEqualSingleQueriesFromSeveralThreads) {
  const SphereEsdfScene& scene = test::sphereEsdfScene();
  const EsdfQuery query(scene.map);
  const std::vector<Eigen::Vector3f> points = randomPoints(20000, 7, true);
  std::vector<EsdfSample> a, b;
  std::thread other([&] { b = query.sample(points); });
  a = query.sample(points);
  other.join();
  const std::vector<std::uint8_t> free = query.isSphereFree(points, 0.1f, 0.05f);
  for (std::size_t i = 0; i < points.size(); i += 7) {
    const EsdfSample single = query.sample(points[i]);
    EXPECT_EQ(a[i].status, single.status);
    EXPECT_EQ(a[i].distance_m, single.distance_m);
    EXPECT_EQ(b[i].distance_m, single.distance_m);
    EXPECT_EQ(free[i] != 0, query.isSphereFree(points[i], 0.1f, 0.05f));
  }
}

}  // namespace
}  // namespace strata

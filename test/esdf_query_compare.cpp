#include "esdf_query_compare.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace strata::test {

std::vector<Eigen::Vector3f> randomPointsIn(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
                                            std::size_t count, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  std::vector<Eigen::Vector3f> points;
  points.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    // One draw each, z first: the order of f(u(rng), u(rng)) is open in C++ (gcc and clang differ).
    const float z = u(rng), y = u(rng), x = u(rng);
    const Eigen::Vector3f t(x, y, z);
    points.push_back(lo + t.cwiseProduct(hi - lo));
  }
  return points;
}

std::vector<Eigen::Vector3f> awayFromVoxelFaces(std::vector<Eigen::Vector3f> points,
                                                float voxel_size_m) {
  constexpr float kGap = 1e-3f;  // voxels
  for (Eigen::Vector3f& p : points) {
    for (int k = 0; k < 3; ++k) {
      const float t = p[k] / voxel_size_m;
      const float frac = t - std::floor(t);
      const bool near_lattice = frac < kGap || frac > 1.0f - kGap || std::fabs(frac - 0.5f) < kGap;
      if (near_lattice) p[k] += 4.0f * kGap * voxel_size_m;
    }
  }
  return points;
}

void appendBadPoints(std::vector<Eigen::Vector3f>& points) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  points.emplace_back(nan, 0.0f, 0.0f);
  points.emplace_back(0.0f, nan, nan);
  points.emplace_back(inf, 0.0f, 0.0f);
  points.emplace_back(0.0f, -inf, 0.0f);
  points.emplace_back(1e20f, 0.0f, 0.0f);
  points.emplace_back(-3e9f, 2e9f, 1e9f);
  points.emplace_back(100.0f, 100.0f, 100.0f);
}

void expectDeviceEqualsHost(const EsdfQuery& host, const std::vector<Eigen::Vector3f>& points,
                            const std::optional<EsdfSphereTest>& spheres,
                            const EsdfQueryResult& device) {
  ASSERT_EQ(device.samples.size(), points.size());
  const std::vector<EsdfSample> expected = host.sample(points);
  std::size_t sample_mismatches = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const EsdfSample& d = device.samples[i];
    const EsdfSample& h = expected[i];
    const bool same = d.status == h.status && d.interpolated == h.interpolated &&
                      std::fabs(d.distance_m - h.distance_m) <= 1e-5f &&
                      (d.gradient - h.gradient).cwiseAbs().maxCoeff() <= 1e-3f;
    if (!same && ++sample_mismatches <= 5) {
      ADD_FAILURE() << "point " << points[i].transpose() << ": device status "
                    << static_cast<int>(d.status) << " d " << d.distance_m << " g "
                    << d.gradient.transpose() << ", host status " << static_cast<int>(h.status)
                    << " d " << h.distance_m << " g " << h.gradient.transpose();
    }
  }
  EXPECT_EQ(sample_mismatches, 0u);
  if (!spheres) return;
  ASSERT_EQ(device.sphere_free.size(), points.size());
  const std::vector<std::uint8_t> free =
      host.isSphereFree(points, spheres->radius_m, spheres->margin_m, spheres->policy);
  std::size_t flag_mismatches = 0, free_count = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    free_count += free[i];
    if (free[i] != device.sphere_free[i]) ++flag_mismatches;
  }
  // NOTE: a sphere whose clearance equals its radius to float rounding may go either way.
  EXPECT_LE(flag_mismatches, points.size() / 1000) << "sphere flags differ";
  EXPECT_GT(free_count, points.size() / 100) << "too few free spheres to compare";
  EXPECT_LT(free_count, points.size() - points.size() / 100) << "too few blocked spheres";
}

}  // namespace strata::test

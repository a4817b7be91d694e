#pragma once
// Shared by the ESDF query tests: random query points and the device-equals-host check.
#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "strata/esdf/esdf_query.h"
#include "strata/esdf/esdf_query_kernel.h"

namespace strata::test {

/// Uniform random points in the box [lo, hi).
std::vector<Eigen::Vector3f> randomPointsIn(const Eigen::Vector3f& lo, const Eigen::Vector3f& hi,
                                            std::size_t count, std::uint32_t seed);

/// Moves every coordinate at least 1e-3 voxel away from voxel faces and centres (the two lattices
/// the queries floor on), so host and device float division cannot pick different voxels.
std::vector<Eigen::Vector3f> awayFromVoxelFaces(std::vector<Eigen::Vector3f> points,
                                                float voxel_size_m);

/// NaN, infinite and far points.
void appendBadPoints(std::vector<Eigen::Vector3f>& points);

/// Device samples and sphere flags equal the host's: status and interpolation exactly, distance
/// within 1e-5 m, gradient within 1e-3; sphere flags on at most 0.1 % of the points (a clearance
/// equal to the radius to float rounding may go either way), with both answers on at least 1 %.
void expectDeviceEqualsHost(const EsdfQuery& host, const std::vector<Eigen::Vector3f>& points,
                            const std::optional<EsdfSphereTest>& spheres,
                            const EsdfQueryResult& device);

}  // namespace strata::test

#pragma once
// Conversions between records and their stored form: poses as 7 doubles (tx ty tz qx qy qz qw),
// 6x6 matrices and feature sets as little-endian blobs.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "strata/store/store_types.h"

namespace strata::store {

/// tx ty tz qx qy qz qw; the quaternion normalised, with qw >= 0.
std::array<double, 7> poseToValues(const Eigen::Isometry3d& T);
/// InputError naming `what` for a non-finite value or a zero quaternion.
Eigen::Isometry3d poseFromValues(const std::array<double, 7>& v, const std::string& what);

/// 36 float64, row-major, little-endian (288 bytes).
std::vector<std::uint8_t> matrixToBlob(const Matrix6d& m);
/// InputError naming `what` for a blob of another size.
Matrix6d matrixFromBlob(const std::vector<std::uint8_t>& blob, const std::string& what);

/// The feature blob (FeatureSet's layout). InputError when descriptors and keypoints disagree.
std::vector<std::uint8_t> featuresToBlob(const FeatureSet& features);
/// InputError naming `what` when the blob's size is not count * (8 + descriptor_bytes).
FeatureSet featuresFromBlob(const std::string& format, std::uint32_t descriptor_bytes,
                            std::size_t count, const std::vector<std::uint8_t>& blob,
                            const std::string& what);

EdgeKind parseEdgeKind(const std::string& name, const std::string& what);
ResourceKind parseResourceKind(const std::string& name, const std::string& what);

}  // namespace strata::store

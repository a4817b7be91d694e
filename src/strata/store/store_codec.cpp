#include "strata/store/store_codec.h"

#include <cmath>
#include <cstring>

#include "strata/core/error.h"

namespace strata::store {

namespace {

// NOTE: blobs are defined little-endian; every platform Strata builds for is, so bytes are copied
// as they are in memory.
static_assert(sizeof(double) == 8 && sizeof(float) == 4, "IEEE-754 sizes");

}  // namespace

const char* edgeKindName(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::kOdometry:
      return "odometry";
    case EdgeKind::kLoop:
      return "loop";
    case EdgeKind::kPrior:
      return "prior";
  }
  return "?";
}

const char* resourceKindName(ResourceKind kind) {
  switch (kind) {
    case ResourceKind::kDepth:
      return "depth";
    case ResourceKind::kColor:
      return "color";
    case ResourceKind::kTsdfLayer:
      return "tsdf_layer";
  }
  return "?";
}

EdgeKind parseEdgeKind(const std::string& name, const std::string& what) {
  for (EdgeKind k : {EdgeKind::kOdometry, EdgeKind::kLoop, EdgeKind::kPrior}) {
    if (name == edgeKindName(k)) return k;
  }
  throw InputError(what + ": unknown edge kind '" + name + "'");
}

ResourceKind parseResourceKind(const std::string& name, const std::string& what) {
  for (ResourceKind k : {ResourceKind::kDepth, ResourceKind::kColor, ResourceKind::kTsdfLayer}) {
    if (name == resourceKindName(k)) return k;
  }
  throw InputError(what + ": unknown resource kind '" + name + "'");
}

std::array<double, 7> poseToValues(const Eigen::Isometry3d& T) {
  Eigen::Quaterniond q(T.rotation());
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d t = T.translation();
  return {t.x(), t.y(), t.z(), q.x(), q.y(), q.z(), q.w()};
}

Eigen::Isometry3d poseFromValues(const std::array<double, 7>& v, const std::string& what) {
  for (double x : v) {
    if (!std::isfinite(x)) throw InputError(what + ": non-finite pose value");
  }
  Eigen::Quaterniond q(v[6], v[3], v[4], v[5]);
  if (q.norm() < 1e-12) throw InputError(what + ": zero quaternion");
  q.normalize();
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.toRotationMatrix();
  T.translation() = Eigen::Vector3d(v[0], v[1], v[2]);
  return T;
}

std::vector<std::uint8_t> matrixToBlob(const Matrix6d& m) {
  std::vector<std::uint8_t> blob(36 * sizeof(double));
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      const double value = m(r, c);
      std::memcpy(blob.data() + (r * 6 + c) * sizeof(double), &value, sizeof(double));
    }
  }
  return blob;
}

Matrix6d matrixFromBlob(const std::vector<std::uint8_t>& blob, const std::string& what) {
  if (blob.size() != 36 * sizeof(double)) {
    throw InputError(what + ": 6x6 matrix blob of " + std::to_string(blob.size()) +
                     " bytes, expected 288");
  }
  Matrix6d m;
  for (int r = 0; r < 6; ++r) {
    for (int c = 0; c < 6; ++c) {
      double value = 0.0;
      std::memcpy(&value, blob.data() + (r * 6 + c) * sizeof(double), sizeof(double));
      m(r, c) = value;
    }
  }
  return m;
}

std::vector<std::uint8_t> featuresToBlob(const FeatureSet& f) {
  const std::size_t n = f.keypoints_px.size();
  if (f.descriptors.size() != n * f.descriptor_bytes) {
    throw InputError("features '" + f.format + "': " + std::to_string(f.descriptors.size()) +
                     " descriptor bytes for " + std::to_string(n) + " keypoints of " +
                     std::to_string(f.descriptor_bytes) + " bytes each");
  }
  const std::size_t record = 8 + f.descriptor_bytes;
  std::vector<std::uint8_t> blob(n * record);
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t* out = blob.data() + i * record;
    const float uv[2] = {f.keypoints_px[i].x(), f.keypoints_px[i].y()};
    std::memcpy(out, uv, 8);
    if (f.descriptor_bytes > 0) {
      std::memcpy(out + 8, f.descriptors.data() + i * f.descriptor_bytes, f.descriptor_bytes);
    }
  }
  return blob;
}

FeatureSet featuresFromBlob(const std::string& format, std::uint32_t descriptor_bytes,
                            std::size_t count, const std::vector<std::uint8_t>& blob,
                            const std::string& what) {
  const std::size_t record = 8 + descriptor_bytes;
  if (blob.size() != count * record) {
    throw InputError(what + ": feature blob of " + std::to_string(blob.size()) + " bytes for " +
                     std::to_string(count) + " records of " + std::to_string(record) + " bytes");
  }
  FeatureSet f;
  f.format = format;
  f.descriptor_bytes = descriptor_bytes;
  f.keypoints_px.resize(count);
  f.descriptors.resize(count * descriptor_bytes);
  for (std::size_t i = 0; i < count; ++i) {
    const std::uint8_t* in = blob.data() + i * record;
    float uv[2];
    std::memcpy(uv, in, 8);
    f.keypoints_px[i] = Eigen::Vector2f(uv[0], uv[1]);
    if (descriptor_bytes > 0) {
      std::memcpy(f.descriptors.data() + i * descriptor_bytes, in + 8, descriptor_bytes);
    }
  }
  return f;
}

}  // namespace strata::store

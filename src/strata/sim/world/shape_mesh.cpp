#include "strata/sim/world/shape_mesh.h"

#include <algorithm>
#include <cmath>
#include "strata/core/math_constants.h"
#include "strata/sim/world/procedural_shapes.h"

namespace strata::sim {
namespace {

using V3 = Eigen::Vector3d;

/// Box from centre-footprint coordinates: x in [x0, x1], y in [y0, y1], z in [z0, z1].
Mesh slab(double x0, double x1, double y0, double y1, double z0, double z1) {
  return boxMesh(V3(x0, y0, z0), V3(x1, y1, z1));
}

/// Chair: four legs, a seat at half the height, a back on the +y edge above the seat.
std::vector<Mesh> chairParts(const V3& size) {
  const double hx = size.x() / 2, hy = size.y() / 2, h = size.z();
  const double seat_top = 0.5 * h, seat = std::min(0.05, 0.1 * h);
  const double leg = std::min(0.04, 0.2 * std::min(size.x(), size.y()));
  const double back = std::min(0.05, 0.2 * size.y());
  std::vector<Mesh> parts;
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      const double x = sx * (hx - leg / 2), y = sy * (hy - leg / 2);
      parts.push_back(slab(x - leg / 2, x + leg / 2, y - leg / 2, y + leg / 2, 0, seat_top - seat));
    }
  }
  parts.push_back(slab(-hx, hx, -hy, hy, seat_top - seat, seat_top));
  parts.push_back(slab(-hx, hx, hy - back, hy, seat_top, h));
  return parts;
}

/// Table: a top slab on four legs inset from the corners.
std::vector<Mesh> tableParts(const V3& size) {
  const double hx = size.x() / 2, hy = size.y() / 2, h = size.z();
  const double top = std::min(0.04, 0.2 * h);
  const double leg = std::min(0.06, 0.2 * std::min(size.x(), size.y()));
  const double inset = leg / 2;
  std::vector<Mesh> parts;
  for (const double sx : {-1.0, 1.0}) {
    for (const double sy : {-1.0, 1.0}) {
      const double x = sx * (hx - inset - leg / 2), y = sy * (hy - inset - leg / 2);
      parts.push_back(slab(x - leg / 2, x + leg / 2, y - leg / 2, y + leg / 2, 0, h - top));
    }
  }
  parts.push_back(slab(-hx, hx, -hy, hy, h - top, h));
  return parts;
}

/// Shelf: two full sides, a back panel on +y, and `levels` boards between the sides.
std::vector<Mesh> shelfParts(const V3& size, int levels) {
  const double hx = size.x() / 2, hy = size.y() / 2, h = size.z();
  const double t = std::min(0.025, 0.1 * std::min(size.x(), size.y()));
  const double board = std::min(t, h / (2.0 * levels));
  std::vector<Mesh> parts;
  parts.push_back(slab(-hx, -hx + t, -hy, hy, 0, h));
  parts.push_back(slab(hx - t, hx, -hy, hy, 0, h));
  parts.push_back(slab(-hx + t, hx - t, hy - t, hy, 0, h));
  for (int i = 0; i < levels; ++i) {
    const double z0 = (h - board) * i / (levels - 1);
    parts.push_back(slab(-hx + t, hx - t, -hy, hy - t, z0, z0 + board));
  }
  return parts;
}

}  // namespace

Mesh boxMesh(const Eigen::Vector3d& min_m, const Eigen::Vector3d& max_m) {
  Mesh mesh;
  for (int i = 0; i < 8; ++i) {  // vertex i: bit 0 -> x max, bit 1 -> y max, bit 2 -> z max
    mesh.vertices.emplace_back((i & 1 ? max_m : min_m).x(), (i & 2 ? max_m : min_m).y(),
                               (i & 4 ? max_m : min_m).z());
  }
  mesh.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 5}, {0, 5, 4},
                    {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return mesh;
}

Mesh cylinderMesh(double radius_m, double z0_m, double z1_m, int segments) {
  Mesh mesh;
  mesh.vertices.emplace_back(0.0f, 0.0f, static_cast<float>(z0_m));  // 0: bottom centre
  mesh.vertices.emplace_back(0.0f, 0.0f, static_cast<float>(z1_m));  // 1: top centre
  for (const double z : {z0_m, z1_m}) {  // rings: bottom 2.., top 2 + segments..
    for (int i = 0; i < segments; ++i) {
      const double angle = 2.0 * kPi * i / segments;
      mesh.vertices.emplace_back(radius_m * std::cos(angle), radius_m * std::sin(angle), z);
    }
  }
  const int n = segments;
  for (int i = 0; i < n; ++i) {
    const int b0 = 2 + i, b1 = 2 + (i + 1) % n, t0 = b0 + n, t1 = b1 + n;
    mesh.triangles.emplace_back(b0, b1, t1);
    mesh.triangles.emplace_back(b0, t1, t0);
    mesh.triangles.emplace_back(0, b1, b0);
    mesh.triangles.emplace_back(1, t0, t1);
  }
  return mesh;
}

std::vector<Mesh> shapeParts(const ShapeSpec& shape, const Mesh* loaded) {
  const V3& s = shape.size_m;
  switch (shape.kind) {
    case ShapeKind::kBox:
      return {slab(-s.x() / 2, s.x() / 2, -s.y() / 2, s.y() / 2, 0, s.z())};
    case ShapeKind::kCylinder:
      return {cylinderMesh(shape.radius_m, 0.0, s.z(), shape.segments)};
    case ShapeKind::kChair:
      return chairParts(s);
    case ShapeKind::kTable:
      return tableParts(s);
    case ShapeKind::kShelf:
      return shelfParts(s, shape.levels);
    case ShapeKind::kMesh:
      return loaded != nullptr ? std::vector<Mesh>{*loaded} : std::vector<Mesh>{};
    case ShapeKind::kVase:
    case ShapeKind::kBlob:
    case ShapeKind::kTube:
    case ShapeKind::kLShape:
    case ShapeKind::kUShape:
    case ShapeKind::kStool:
      return proceduralParts(shape);
  }
  return {};
}

void appendMesh(const Mesh& part, const Eigen::Isometry3d& T_W_P,
                const std::array<std::uint8_t, 3>& albedo, Mesh& out) {
  const int base = static_cast<int>(out.vertices.size());
  const Eigen::Isometry3f T = T_W_P.cast<float>();
  for (const Eigen::Vector3f& v : part.vertices) {
    out.vertices.push_back(T * v);
    out.colors.push_back(albedo);
  }
  for (const Eigen::Vector3i& t : part.triangles)
    out.triangles.push_back(t + Eigen::Vector3i::Constant(base));
}

Eigen::Isometry3d floorPose(const Eigen::Vector2d& at_m, double yaw_deg) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() =
      Eigen::AngleAxisd(yaw_deg * kPi / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(at_m.x(), at_m.y(), 0.0);
  return T;
}

}  // namespace strata::sim

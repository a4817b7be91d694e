#include "objects_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "strata/map/block_index.h"
#include "strata/sim/world/shape_mesh.h"
#include "strata/sim/world/triangle_distance.h"

namespace strata::bench {
namespace {

constexpr float kVoxelM = 0.02f;

/// Signed distance to a shape made of closed convex parts (every part of shapeParts is a box or
/// a prism): inside a part, the largest face-plane distance (exact for a convex solid); outside,
/// the nearest triangle. Far points (beyond the part's box by more than `far_m`) get the
/// distance to that box, a lower bound that the truncation hides anyway.
class ShapeSdf {
 public:
  ShapeSdf(const std::vector<Mesh>& parts, float far_m) : far_m_(far_m) {
    for (const Mesh& mesh : parts) {
      Part part;
      for (const Eigen::Vector3f& v : mesh.vertices) part.box.extend(v.cast<double>());
      for (const Eigen::Vector3i& t : mesh.triangles) {
        const Eigen::Vector3d a = mesh.vertices[t.x()].cast<double>();
        const Eigen::Vector3d b = mesh.vertices[t.y()].cast<double>();
        const Eigen::Vector3d c = mesh.vertices[t.z()].cast<double>();
        const Eigen::Vector3d n = (b - a).cross(c - a);
        if (n.norm() < 1e-12) continue;
        part.triangles.push_back({a, b, c, n.normalized()});
      }
      parts_.push_back(std::move(part));
    }
  }

  double operator()(const Eigen::Vector3d& p) const {
    double best = std::numeric_limits<double>::infinity();
    for (const Part& part : parts_) best = std::min(best, partDistance(part, p));
    return best;
  }

 private:
  struct Triangle {
    Eigen::Vector3d a, b, c, n;
  };
  struct Part {
    Eigen::AlignedBox3d box;
    std::vector<Triangle> triangles;
  };

  double partDistance(const Part& part, const Eigen::Vector3d& p) const {
    const double box_distance = part.box.exteriorDistance(p);
    if (box_distance > far_m_) return box_distance;
    double plane = -std::numeric_limits<double>::infinity();
    for (const Triangle& t : part.triangles) plane = std::max(plane, t.n.dot(p - t.a));
    if (plane <= 0.0) return plane;
    double nearest = std::numeric_limits<double>::infinity();
    for (const Triangle& t : part.triangles) {
      nearest = std::min(nearest, (sim::closestPointOnTriangle(p, t.a, t.b, t.c) - p).norm());
    }
    return nearest;
  }

  float far_m_;
  std::vector<Part> parts_;
};

sim::ShapeSpec randomSpec(std::mt19937& rng) {
  const auto u = [&](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  sim::ShapeSpec s;
  switch (std::uniform_int_distribution<int>(0, 4)(rng)) {
    case 0:
      s.kind = sim::ShapeKind::kBox;
      s.size_m = {u(0.25, 0.8), u(0.25, 0.8), u(0.25, 0.8)};
      break;
    case 1:
      s.kind = sim::ShapeKind::kCylinder;
      s.radius_m = u(0.12, 0.35);
      s.size_m = {2 * s.radius_m, 2 * s.radius_m, u(0.3, 1.0)};
      s.segments = 24;
      break;
    case 2:
      s.kind = sim::ShapeKind::kChair;
      s.size_m = {u(0.42, 0.6), u(0.42, 0.6), u(0.8, 1.0)};
      break;
    case 3:
      s.kind = sim::ShapeKind::kTable;
      s.size_m = {u(0.6, 1.4), u(0.5, 0.9), u(0.7, 0.8)};
      break;
    default:
      s.kind = sim::ShapeKind::kShelf;
      s.size_m = {u(0.6, 1.0), u(0.3, 0.4), u(0.9, 1.4)};
      s.levels = std::uniform_int_distribution<int>(3, 5)(rng);
      break;
  }
  return s;
}

}  // namespace

std::vector<BenchShape> benchShapes(int count) {
  // Office-like colours: wood, grey and black plastic, white, a few bright ones.
  const std::array<std::array<std::uint8_t, 3>, 8> palette = {{{200, 60, 50},
                                                               {50, 90, 180},
                                                               {60, 150, 70},
                                                               {220, 200, 60},
                                                               {140, 95, 55},
                                                               {150, 150, 150},
                                                               {230, 230, 225},
                                                               {40, 40, 45}}};
  std::mt19937 rng(7);
  std::vector<BenchShape> shapes;
  for (int i = 0; i < count; ++i) {
    BenchShape s;
    s.spec = randomSpec(rng);
    s.albedo = palette[std::uniform_int_distribution<std::size_t>(0, palette.size() - 1)(rng)];
    shapes.push_back(s);
  }
  return shapes;
}

ObjectSession objectSession(const BenchShape& shape, double yaw_deg, View view, int session) {
  MapConfig config;
  config.voxel_size_m = kVoxelM;
  const double trunc = config.truncationDistance();
  const Eigen::Isometry3d T_W_P = sim::floorPose(Eigen::Vector2d::Zero(), yaw_deg);
  const Eigen::Isometry3d T_P_W = T_W_P.inverse();
  const ShapeSdf shape_sdf(sim::shapeParts(shape.spec), static_cast<float>(2 * trunc));
  const double reach = 0.5 * std::hypot(shape.spec.size_m.x(), shape.spec.size_m.y()) + 0.3;
  const Eigen::Vector3d lo(-reach, -reach, -0.1), hi(reach, reach, shape.spec.size_m.z() + 0.15);
  const auto observed = [&](const Eigen::Vector3d& p_W, double d_shape) {
    if ((p_W.head<2>().array().abs() > reach - 0.05).any()) return false;  // the map's rim
    return view == View::kComplete || d_shape >= 0.15 || (T_P_W * p_W).y() < 0.02;
  };
  ObjectSession s;
  s.map = TsdfMap(config);
  change::LabelMap labels;
  labels.voxel_size_m = kVoxelM;
  const float block_m = config.blockSize();
  const BlockIndex b0 = (lo.cast<float>() / block_m).array().floor().cast<int>();
  const BlockIndex b1 = (hi.cast<float>() / block_m).array().floor().cast<int>();
  const std::uint32_t grey = packRgb(128, 128, 128);
  const std::uint32_t albedo = packRgb(shape.albedo[0], shape.albedo[1], shape.albedo[2]);
  for (int bz = b0.z(); bz <= b1.z(); ++bz) {
    for (int by = b0.y(); by <= b1.y(); ++by) {
      for (int bx = b0.x(); bx <= b1.x(); ++bx) {
        const BlockIndex b(bx, by, bz);
        TsdfBlock& block = s.map.allocateBlock(b);
        change::LabelBlock& label = labels.allocateBlock(b);
        for (int i = 0; i < kVoxelsPerBlock; ++i) {
          const Eigen::Vector3i local(i % 8, i / 8 % 8, i / 64);
          const Eigen::Vector3d p = voxelCenter(b * kBlockEdge + local, kVoxelM).cast<double>();
          const double d_shape = shape_sdf(T_P_W * p);
          const double d = std::min(p.z(), d_shape);
          block[i].tsdf_m = static_cast<float>(std::clamp(d, -trunc, trunc));
          block[i].weight = (d > -trunc && observed(p, d_shape)) ? 20.0f : 0.0f;
          block[i].color_rgba = d_shape < 3 * kVoxelM ? albedo : grey;
          label[static_cast<std::size_t>(i)] =
              d_shape < 3 * kVoxelM ? change::VoxelLabel::kDynamic : change::VoxelLabel::kStatic;
        }
      }
    }
  }
  s.segments =
      change::extractObjects(s.map, labels, change::ObjectConfig{}, session, nullptr, &s.surface);
  return s;
}

}  // namespace strata::bench

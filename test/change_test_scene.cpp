#include "change_test_scene.h"

#include <algorithm>
#include <initializer_list>

namespace strata::test {

double boxSdf(const Eigen::Vector3d& p, const Eigen::AlignedBox3d& box) {
  const Eigen::Vector3d c = box.center(), h = 0.5 * box.sizes();
  const Eigen::Vector3d q = (p - c).cwiseAbs() - h;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

TsdfMap makeSdfMap(const Sdf& sdf, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                   float voxel_size_m, const PointTest& observed) {
  MapConfig config;
  config.voxel_size_m = voxel_size_m;
  TsdfMap map(config);
  const double trunc = config.truncationDistance();
  const float block_m = config.blockSize();
  const BlockIndex b0 = (lo.cast<float>() / block_m).array().floor().cast<int>();
  const BlockIndex b1 = (hi.cast<float>() / block_m).array().floor().cast<int>();
  for (int bz = b0.z(); bz <= b1.z(); ++bz) {
    for (int by = b0.y(); by <= b1.y(); ++by) {
      for (int bx = b0.x(); bx <= b1.x(); ++bx) {
        const BlockIndex b(bx, by, bz);
        TsdfBlock& block = map.allocateBlock(b);
        for (int i = 0; i < kVoxelsPerBlock; ++i) {
          const Eigen::Vector3i local(i % 8, i / 8 % 8, i / 64);
          const Eigen::Vector3d p =
              voxelCenter(b * kBlockEdge + local, voxel_size_m).cast<double>();
          const double d = sdf(p);
          block[i].tsdf_m = static_cast<float>(std::clamp(d, -trunc, trunc));
          block[i].weight = (d > -trunc && observed(p)) ? 20.0f : 0.0f;
          block[i].color_rgba = packRgb(128, 128, 128);
        }
      }
    }
  }
  return map;
}

change::LabelMap makeLabels(const TsdfMap& map, const PointTest& dynamic) {
  change::LabelMap labels;
  labels.voxel_size_m = map.config().voxel_size_m;
  for (const auto& [b, block] : map.blocks()) {
    change::LabelBlock& out = labels.blocks[b];
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      const Eigen::Vector3i local(i % 8, i / 8 % 8, i / 64);
      const Eigen::Vector3d p =
          voxelCenter(b * kBlockEdge + local, labels.voxel_size_m).cast<double>();
      out[static_cast<std::size_t>(i)] =
          dynamic(p) ? change::VoxelLabel::kDynamic : change::VoxelLabel::kStatic;
    }
  }
  return labels;
}

Mesh boxMesh(const Eigen::AlignedBox3d& box) {
  Mesh mesh;
  for (int c = 0; c < 8; ++c) {
    mesh.vertices.push_back(
        box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).cast<float>());
  }
  // Corner c has bit 0 = x max, bit 1 = y max, bit 2 = z max; quads listed
  // inward, so triangles wind them backwards (outward normals).
  const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                           {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (const auto& q : faces) {
    mesh.triangles.emplace_back(q[0], q[2], q[1]);
    mesh.triangles.emplace_back(q[0], q[3], q[2]);
  }
  return mesh;
}

namespace {

const Eigen::AlignedBox3d kPebble(Eigen::Vector3d(1.5, 0.3, -0.1),
                                  Eigen::Vector3d(1.54, 0.34, 0.04));
const Eigen::AlignedBox3d kPoster(Eigen::Vector3d(1.85, 0.2, 0.5), Eigen::Vector3d(1.95, 0.8, 1.0));
const Eigen::AlignedBox3d kFloorNoise(Eigen::Vector3d(0.2, 1.5, -0.1),
                                      Eigen::Vector3d(0.4, 1.7, 0.06));

double objectsSceneSdf(const Eigen::Vector3d& p) {
  double d = p.z();  // the floor
  for (const auto* box : {&kBoxA, &kBoxB, &kPebble}) d = std::min(d, boxSdf(p, *box));
  if (kPoster.contains(p)) d = std::min(d, p.x() - 1.9);  // only its front: an open panel
  return d;
}

bool nearAny(const Eigen::Vector3d& p, std::initializer_list<const Eigen::AlignedBox3d*> boxes,
             double margin) {
  return std::any_of(boxes.begin(), boxes.end(),
                     [&](const auto* b) { return boxSdf(p, *b) < margin; });
}

}  // namespace

ObjectsScene makeObjectsScene() {
  const auto observed = [](const Eigen::Vector3d& p) {
    return p.x() > 0.05 && p.y() > 0.05 && p.x() < 1.95 && p.y() < 1.95 &&
           (!kPoster.contains(p) || p.x() > 1.9 - 0.03);
  };
  TsdfMap map = makeSdfMap(objectsSceneSdf, {0, 0, -0.1}, {2, 2, 1.1}, kVoxel, observed);
  // Three voxels around each moved thing, like the dilated label layer.
  change::LabelMap labels = makeLabels(map, [](const Eigen::Vector3d& p) {
    return nearAny(p, {&kBoxA, &kBoxB, &kPebble, &kFloorNoise}, 3 * kVoxel) || kPoster.contains(p);
  });
  return {std::move(map), std::move(labels)};
}

}  // namespace strata::test

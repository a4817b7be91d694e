// Vertex and face labels of object discovery, from the voxel labels of a session's dynamic part.
#include <cmath>

#include "strata/change/internal/objects_steps.h"

namespace strata::change::detail {
namespace {

/// Label lookups with the last block remembered: mesh vertices come in block order, so most
/// lookups hit the same block as the one before.
class LabelLookup {
 public:
  explicit LabelLookup(const LabelMap& labels) : labels_(labels) {}

  bool dynamic(const GlobalVoxelIndex& v) {
    const BlockIndex b = blockOfVoxel(v);
    if (block_ == nullptr || b != block_index_) {
      const auto it = labels_.blocks.find(b);
      block_index_ = b;
      block_ = it == labels_.blocks.end() ? nullptr : &it->second;
      if (block_ == nullptr) return false;
    }
    const Eigen::Vector3i local = v - b * kBlockEdge;
    return (*block_)[static_cast<std::size_t>(linearVoxelIndex(local.x(), local.y(), local.z()))] ==
           VoxelLabel::kDynamic;
  }

 private:
  const LabelMap& labels_;
  BlockIndex block_index_ = BlockIndex::Zero();
  const LabelBlock* block_ = nullptr;
};

/// Dynamic share of the trilinear weights of the 8 voxel centres around p.
float dynamicShare(LabelLookup& lookup, const Eigen::Vector3f& p, float voxel_size_m) {
  // Voxel centres sit at (i + 0.5) * voxel_size: shift so they fall on integers.
  const Eigen::Vector3f q = p / voxel_size_m - Eigen::Vector3f::Constant(0.5f);
  const Eigen::Vector3f base = q.array().floor();
  const Eigen::Vector3f f = q - base;
  const Eigen::Vector3i b = base.cast<int>();
  float share = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3i d(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
    float w = 1.0f;
    for (int k = 0; k < 3; ++k) w *= d[k] ? f[k] : 1.0f - f[k];
    if (w > 0.0f && lookup.dynamic(b + d)) share += w;
  }
  return share;
}

}  // namespace

std::vector<bool> labelVertices(const Mesh& mesh, const LabelMap& labels, float vote) {
  LabelLookup lookup(labels);
  std::vector<bool> dynamic(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    dynamic[i] = dynamicShare(lookup, mesh.vertices[i], labels.voxel_size_m) >= vote;
  }
  return dynamic;
}

std::vector<bool> labelFaces(const Mesh& mesh, const std::vector<bool>& vertex_dynamic) {
  std::vector<bool> dynamic(mesh.triangles.size());
  for (std::size_t f = 0; f < mesh.triangles.size(); ++f) {
    const Eigen::Vector3i& t = mesh.triangles[f];
    int votes = 0;
    for (int k = 0; k < 3; ++k) votes += vertex_dynamic[static_cast<std::size_t>(t[k])] ? 1 : 0;
    dynamic[f] = votes >= 2;
  }
  return dynamic;
}

}  // namespace strata::change::detail

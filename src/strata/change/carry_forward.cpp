#include "strata/change/carry_forward.h"

#include <cmath>
#include <string>

#include "strata/core/error.h"

namespace strata::change {
namespace {

void requireSameVoxelSize(const TsdfMap& a, const TsdfMap& b, const char* what) {
  if (std::fabs(a.config().voxel_size_m - b.config().voxel_size_m) > 1e-7f) {
    throw InputError(std::string(what) + ": the maps have different voxel sizes (" +
                     std::to_string(a.config().voxel_size_m) + " and " +
                     std::to_string(b.config().voxel_size_m) + " m)");
  }
}

}  // namespace

CarryStats carryObserved(const TsdfMap& latest, const std::vector<ConfirmedPoint>& points,
                         float min_weight, TsdfMap& session, const VoxelSet* own) {
  requireSameVoxelSize(latest, session, "carryObserved");
  const float voxel_m = session.config().voxel_size_m;
  CarryStats stats;
  stats.points = points.size();
  for (const ConfirmedPoint& point : points) {
    if (!point.p_W.allFinite() || !(point.radius_m >= 0.0f)) continue;
    const Eigen::Vector3f centre_vox = point.p_W / voxel_m;  // in voxel units
    const float radius_vox = point.radius_m / voxel_m;
    const Eigen::Vector3i lo = (centre_vox.array() - radius_vox).floor().cast<int>();
    const Eigen::Vector3i hi = (centre_vox.array() + radius_vox).floor().cast<int>();
    for (int z = lo.z(); z <= hi.z(); ++z) {
      for (int y = lo.y(); y <= hi.y(); ++y) {
        for (int x = lo.x(); x <= hi.x(); ++x) {
          const GlobalVoxelIndex v(x, y, z);
          const Eigen::Vector3f centre = v.cast<float>().array() + 0.5f;
          if ((centre - centre_vox).squaredNorm() > radius_vox * radius_vox) continue;
          const TsdfVoxel* from = latest.findVoxel(v);
          if (from == nullptr || from->weight < min_weight) continue;
          const TsdfVoxel* present = session.findVoxel(v);
          if (present != nullptr && present->weight >= min_weight) continue;
          if (own != nullptr && own->count(v) > 0) continue;
          session.allocateVoxel(v) = *from;
          ++stats.voxels;
        }
      }
    }
  }
  return stats;
}

void keepLatestObserved(const TsdfMap& session, float min_weight, TsdfMap& latest) {
  requireSameVoxelSize(latest, session, "keepLatestObserved");
  for (const auto& [index, block] : session.blocks()) {
    TsdfBlock* into = nullptr;
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      if (block[i].weight < min_weight) continue;
      if (into == nullptr) into = &latest.allocateBlock(index);
      (*into)[i] = block[i];
    }
  }
}

}  // namespace strata::change

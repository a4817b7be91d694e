#include "strata/esdf/esdf_compare.h"

#include <cmath>

namespace strata {

bool EsdfAgreement::ok() const {
  return compared == 0 || (static_cast<double>(over_voxel) <= kEsdfMaxShareOverVoxel * compared &&
                           mean_abs_voxels < kEsdfMaxMeanErrorVoxels);
}

EsdfAgreement compareEsdfWithReference(const EsdfMap& esdf, const EsdfMap& reference) {
  EsdfAgreement a;
  double sum = 0.0;
  for (const auto& [b, block] : reference.blocks) {
    const auto it = esdf.blocks.find(b);
    for (int i = 0; i < kVoxelsPerBlock; ++i) {
      if (!esdfObserved(block[i]) || !esdfHasSite(block[i])) continue;
      const float d = it == esdf.blocks.end() ? 0.0f : it->second[i].distance_m;
      const double error = std::fabs(d - block[i].distance_m) / reference.voxel_size_m;
      ++a.compared;
      sum += error;
      a.over_voxel += error > 1.0 ? 1 : 0;
    }
  }
  a.mean_abs_voxels = a.compared > 0 ? sum / static_cast<double>(a.compared) : 0.0;
  return a;
}

}  // namespace strata

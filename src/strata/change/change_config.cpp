#include "strata/change/change_config.h"

#include <cmath>
#include <string>

#include "strata/core/error.h"

namespace strata::change {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw InputError("ChangeConfig: " + what);
}

void requireKernel(int voxels, const char* field) {
  // Radius <= 3 keeps the neighbourhood inside the 3x3x3 blocks around a block (8 voxels wide)
  // and the shared-memory tile of the device kernels small.
  require(voxels >= 1 && voxels <= 7 && voxels % 2 == 1,
          std::string(field) + " must be odd and in [1, 7] voxels, got " + std::to_string(voxels));
}

}  // namespace

ChangeConfig ChangeConfig::forSubsampling(double recorded_per_fused) const {
  require(std::isfinite(recorded_per_fused) && recorded_per_fused >= 1.0,
          "recorded frames per fused frame must be >= 1, got " +
              std::to_string(recorded_per_fused));
  ChangeConfig scaled = *this;
  scaled.min_weight = static_cast<float>(min_weight / recorded_per_fused);
  return scaled;
}

void ChangeConfig::validate(float voxel_size_m) const {
  require(std::isfinite(voxel_size_m) && voxel_size_m > 0.0f, "voxel size must be > 0");
  require(std::isfinite(min_weight) && min_weight > 0.0f,
          "min_weight must be > 0, got " + std::to_string(min_weight));
  require(std::isfinite(difference_threshold_m) && difference_threshold_m > 0.0f,
          "difference_threshold_m must be > 0, got " + std::to_string(difference_threshold_m));
  require(
      std::isfinite(merge_close_m) && merge_close_m >= 0.0f &&
          merge_close_m < difference_threshold_m,
      "merge_close_m must be in [0, difference_threshold_m), got " + std::to_string(merge_close_m));
  requireKernel(erosion_kernel_voxels, "erosion_kernel_voxels");
  requireKernel(dilation_kernel_voxels, "dilation_kernel_voxels");
}

MapConfig changeMapConfig(float voxel_size_m) {
  MapConfig config;
  config.voxel_size_m = voxel_size_m;
  config.allocate_free_space = true;
  config.weight_mode = WeightMode::kConstant;
  config.validate();
  return config;
}

}  // namespace strata::change

#include "strata/track/depth_filter.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "strata/map/camera_math.h"

namespace strata {
namespace {

/// exp(-(du² + dv²) / 2 sigma²) over the (2 radius + 1)² window, row by row.
std::vector<float> spatialWeights(int radius, float sigma_px) {
  const int side = 2 * radius + 1;
  std::vector<float> weights(static_cast<std::size_t>(side) * side);
  for (int dv = -radius; dv <= radius; ++dv) {
    for (int du = -radius; du <= radius; ++du) {
      weights[static_cast<std::size_t>(dv + radius) * side + (du + radius)] =
          std::exp(-static_cast<float>(du * du + dv * dv) / (2.0f * sigma_px * sigma_px));
    }
  }
  return weights;
}

}  // namespace

DepthImage bilateralFilterDepth(const DepthImage& depth, const MapConfig& map, float sigma_px,
                                float sigma_share) {
  DepthImage out(depth.width_px, depth.height_px);
  const auto valid = [&](float d) { return depthValid(d, map.min_depth_m, map.max_depth_m); };
  if (!(sigma_px > 0.0f)) {
    for (std::size_t i = 0; i < depth.depth_m.size(); ++i) {
      if (valid(depth.depth_m[i])) out.depth_m[i] = depth.depth_m[i];
    }
    return out;
  }
  const int radius = static_cast<int>(std::ceil(2.0f * sigma_px));
  const int side = 2 * radius + 1;
  const std::vector<float> spatial = spatialWeights(radius, sigma_px);
  for (int v = 0; v < depth.height_px; ++v) {
    for (int u = 0; u < depth.width_px; ++u) {
      const float d = depth.at(u, v);
      if (!valid(d)) continue;
      const float sigma_m = sigma_share * d;
      const float inv_two_var = 1.0f / (2.0f * sigma_m * sigma_m);
      const float cutoff = 3.0f * sigma_m;  // weights beyond are under 1.2 %: skip the exp
      float weight_sum = 0.0f;
      float depth_sum = 0.0f;
      for (int dv = std::max(-radius, -v); dv <= std::min(radius, depth.height_px - 1 - v); ++dv) {
        const float* row = &depth.depth_m[static_cast<std::size_t>(v + dv) * depth.width_px];
        const float* row_weights = &spatial[static_cast<std::size_t>(dv + radius) * side + radius];
        for (int du = std::max(-radius, -u); du <= std::min(radius, depth.width_px - 1 - u); ++du) {
          const float q = row[u + du];
          const float diff = q - d;
          if (std::abs(diff) > cutoff || !valid(q)) continue;
          const float w = row_weights[du] * std::exp(-diff * diff * inv_two_var);
          weight_sum += w;
          depth_sum += w * q;
        }
      }
      out.at(u, v) = depth_sum / weight_sum;  // the centre itself weighs 1
    }
  }
  return out;
}

}  // namespace strata

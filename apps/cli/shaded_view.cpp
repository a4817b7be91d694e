#include "cli/shaded_view.h"

#include <algorithm>

namespace strata::apps {

ColorImage shadedView(const RaycastImage& image, const Eigen::Isometry3d& T_W_C) {
  const int w = image.depth.width_px;
  const int h = image.depth.height_px;
  ColorImage out(w, h);
  const Eigen::Vector3f toward_camera_W = -(T_W_C.rotation().col(2)).cast<float>();
  for (std::size_t i = 0; i < image.hit.size(); ++i) {
    std::uint8_t* rgb = &out.rgb[i * 3];
    if (image.hit[i] == 0) {
      rgb[0] = 20, rgb[1] = 24, rgb[2] = 48;
      continue;
    }
    const float lambert = std::max(0.0f, image.normal_W[i].dot(toward_camera_W));
    const float shade = 0.25f + 0.75f * lambert;
    const std::uint8_t* albedo = &image.color.rgb[i * 3];
    const bool has_color = albedo[0] != 0 || albedo[1] != 0 || albedo[2] != 0;
    for (int c = 0; c < 3; ++c) {
      const float base = has_color ? static_cast<float>(albedo[c]) : 200.0f;
      rgb[c] = static_cast<std::uint8_t>(std::clamp(base * shade, 0.0f, 255.0f));
    }
  }
  return out;
}

}  // namespace strata::apps

#include "cli/diff_overlay_raster.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace strata::apps::overlay_detail {
namespace {

struct ScreenTriangle {
  Eigen::Vector2f p[3];
  float z[3];
};

float edge(const Eigen::Vector2f& a, const Eigen::Vector2f& b, const Eigen::Vector2f& p) {
  return (b.x() - a.x()) * (p.y() - a.y()) - (b.y() - a.y()) * (p.x() - a.x());
}

void fillTriangle(TopImage& image, const ScreenTriangle& t, Rgb colour, float z_bias_m) {
  const float area = edge(t.p[0], t.p[1], t.p[2]);
  if (std::abs(area) < 1e-12f) return;
  const TopView& v = image.view;
  const auto lo = t.p[0].cwiseMin(t.p[1]).cwiseMin(t.p[2]);
  const auto hi = t.p[0].cwiseMax(t.p[1]).cwiseMax(t.p[2]);
  const int x0 = std::max(0, static_cast<int>(std::floor(lo.x())));
  const int y0 = std::max(0, static_cast<int>(std::floor(lo.y())));
  const int x1 = std::min(v.width - 1, static_cast<int>(std::ceil(hi.x())));
  const int y1 = std::min(v.height - 1, static_cast<int>(std::ceil(hi.y())));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const Eigen::Vector2f c(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
      // Barycentric weights; the sign of `area` absorbs either winding after projection.
      const float w0 = edge(t.p[1], t.p[2], c) / area;
      const float w1 = edge(t.p[2], t.p[0], c) / area;
      const float w2 = 1.0f - w0 - w1;
      if (w0 < 0.0f || w1 < 0.0f || w2 < 0.0f) continue;
      const float z = w0 * t.z[0] + w1 * t.z[1] + w2 * t.z[2];
      const std::size_t i = static_cast<std::size_t>(y) * v.width + x;
      if (z > image.z[i] + z_bias_m) {
        image.z[i] = z;
        image.colour[i] = colour;
      }
    }
  }
}

Rgb shade(Rgb base, float normal_z) {
  // Up-facing faces bright, walls and sides darker: reads as relief from above.
  const float f = 0.55f + 0.45f * std::clamp(normal_z, 0.0f, 1.0f);
  Rgb out;
  for (int k = 0; k < 3; ++k) out[k] = static_cast<std::uint8_t>(std::lround(base[k] * f));
  return out;
}

}  // namespace

TopImage makeTopImage(const TopView& view) {
  TopImage image;
  image.view = view;
  const std::size_t n = static_cast<std::size_t>(view.width) * view.height;
  image.z.assign(n, -std::numeric_limits<float>::infinity());
  image.colour.assign(n, Rgb{{255, 255, 255}});
  return image;
}

void drawMesh(TopImage& image, const Mesh& mesh, Rgb base, float z_bias_m) {
  for (const Eigen::Vector3i& tri : mesh.triangles) {
    const Eigen::Vector3f& a = mesh.vertices[static_cast<std::size_t>(tri[0])];
    const Eigen::Vector3f& b = mesh.vertices[static_cast<std::size_t>(tri[1])];
    const Eigen::Vector3f& c = mesh.vertices[static_cast<std::size_t>(tri[2])];
    const Eigen::Vector3f n = (b - a).cross(c - a);
    const float length = n.norm();
    if (length <= 0.0f) continue;
    const float normal_z = n.z() / length;
    if (normal_z < -0.1f) continue;  // faces down: a ceiling or an underside
    ScreenTriangle t{{image.view.toPixel(a), image.view.toPixel(b), image.view.toPixel(c)},
                     {a.z(), b.z(), c.z()}};
    fillTriangle(image, t, shade(base, normal_z), z_bias_m);
  }
}

}  // namespace strata::apps::overlay_detail

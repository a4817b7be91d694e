#pragma once
// Internal to diff_overlay.cpp: a z-buffered top-down rasteriser of triangles.
#include <Eigen/Core>
#include <vector>

#include "cli/esdf_slice_font.h"
#include "strata/core/types.h"
#include "strata/mesh/mesh.h"

namespace strata::apps::overlay_detail {

/// Orthographic view along -z: world (x, y) -> pixel (column, row), x right, y up.
struct TopView {
  Eigen::Vector2f origin_m = Eigen::Vector2f::Zero();  // world (x, y) of the top-left corner
  float pixel_m = 0.01f;
  int width = 0, height = 0;
  Eigen::Vector2f toPixel(const Eigen::Vector3f& p) const {
    return {(p.x() - origin_m.x()) / pixel_m, (origin_m.y() - p.y()) / pixel_m};
  }
};

/// Colour and height of the top-most surface per pixel.
struct TopImage {
  TopView view;
  std::vector<float> z;  // -inf where nothing was drawn
  std::vector<Rgb> colour;
};

TopImage makeTopImage(const TopView& view);

/// Draws the mesh's upward or sideways faces, each shaded from `base` by its normal's z. A face
/// replaces what is there when it is higher by more than `z_bias_m` below (negative bias lets a
/// later mesh win ties: objects over the surface they were cut from).
void drawMesh(TopImage& image, const Mesh& mesh, Rgb base, float z_bias_m);

}  // namespace strata::apps::overlay_detail

#include "cli/objects_sheet.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "cli/esdf_slice_font.h"
#include "cli/shaded_view.h"
#include "strata/raycast/raycast.h"

namespace strata::apps {
namespace {

constexpr double kFieldOfViewDeg = 45.0;
constexpr Rgb kText = {20, 20, 20};
constexpr int kLabelHeightPx = 36;
constexpr int kGapPx = 4;

/// Camera at `eye` looking at `target`, image up along world +z (x right, y down, z forward).
Eigen::Isometry3d lookAt(const Eigen::Vector3d& eye, const Eigen::Vector3d& target) {
  const Eigen::Vector3d z = (target - eye).normalized();
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d y = -(up - up.dot(z) * z).normalized();
  Eigen::Isometry3d T_W_C = Eigen::Isometry3d::Identity();
  T_W_C.linear().col(0) = y.cross(z);
  T_W_C.linear().col(1) = y;
  T_W_C.linear().col(2) = z;
  T_W_C.translation() = eye;
  return T_W_C;
}

}  // namespace

void pasteTile(ColorImage& sheet, const ColorImage& tile, int x0, int y0) {
  for (int y = 0; y < tile.height_px; ++y) {
    for (int x = 0; x < tile.width_px; ++x) {
      const std::size_t from = (static_cast<std::size_t>(y) * tile.width_px + x) * 3;
      const std::size_t to = (static_cast<std::size_t>(y0 + y) * sheet.width_px + x0 + x) * 3;
      std::copy_n(&tile.rgb[from], 3, &sheet.rgb[to]);
    }
  }
}

ModelCamera modelCamera(const objects::ObjectModel& model, int size_px) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3f& v : model.mesh_M.vertices) box.extend(v.cast<double>());
  if (box.isEmpty()) box.extend(Eigen::Vector3d::Zero());
  const double radius_m = std::max(0.05, 0.5 * box.diagonal().norm());
  const double half_fov = 0.5 * kFieldOfViewDeg * 3.14159265358979323846 / 180.0;
  const double distance_m = 1.1 * radius_m / std::sin(half_fov);
  const Eigen::Vector3d direction = Eigen::Vector3d(-0.6, -0.8, 0.7).normalized();
  ModelCamera camera;
  camera.T_M_C = lookAt(box.center() + distance_m * direction, box.center());
  CameraIntrinsics& k = camera.intrinsics;
  k.width_px = k.height_px = size_px;
  k.fx_px = k.fy_px = static_cast<float>(0.5 * size_px / std::tan(half_fov));
  k.cx_px = k.cy_px = 0.5f * static_cast<float>(size_px) - 0.5f;
  return camera;
}

ColorImage renderTsdfView(const TsdfMap& tsdf, const CameraIntrinsics& intrinsics,
                          const Eigen::Isometry3d& T_F_C) {
  RaycastOptions options;
  options.min_weight = 1e-3f;  // as the model's meshing
  return shadedView(raycastReference(tsdf, intrinsics, T_F_C, options), T_F_C);
}

ColorImage renderModelView(const objects::ObjectModel& model, int size_px) {
  if (model.mesh_M.vertices.empty()) return ColorImage(size_px, size_px, 60);
  const ModelCamera camera = modelCamera(model, size_px);
  return renderTsdfView(model.tsdf, camera.intrinsics, camera.T_M_C);
}

ColorImage renderModelSheet(const std::vector<objects::ObjectModel>& models, int size_px) {
  if (models.empty()) {
    ColorImage empty(320, 40, 255);
    drawText(empty, 8, 12, "NO OBJECT MODEL", 2, kText);
    return empty;
  }
  const int columns = std::min<int>(6, static_cast<int>(models.size()));
  const int rows = (static_cast<int>(models.size()) + columns - 1) / columns;
  ColorImage sheet(columns * (size_px + kGapPx) + kGapPx,
                   rows * (size_px + kLabelHeightPx + kGapPx) + kGapPx, 255);
  for (std::size_t i = 0; i < models.size(); ++i) {
    const objects::ObjectModel& m = models[i];
    const int x0 = kGapPx + static_cast<int>(i % columns) * (size_px + kGapPx);
    const int y0 = kGapPx + static_cast<int>(i / columns) * (size_px + kLabelHeightPx + kGapPx);
    drawText(sheet, x0 + 2, y0 + 2, "MODEL " + std::to_string(m.id), 2, kText);
    drawText(sheet, x0 + 2, y0 + 19,
             std::to_string(m.instances.size()) + " INSTANCES, " +
                 std::to_string(m.merged_observations) + " MERGED",
             1, kText);
    pasteTile(sheet, renderModelView(m, size_px), x0, y0 + kLabelHeightPx);
  }
  return sheet;
}

}  // namespace strata::apps

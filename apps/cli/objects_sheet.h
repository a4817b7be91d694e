#pragma once
// The contact sheet of an object database: one shaded rendering per model (its TSDF raycast from
// above and aside, coloured by the model's colour), labelled with its id and instance count.
#include <Eigen/Geometry>
#include <vector>

#include "strata/core/types.h"
#include "strata/map/tsdf_map.h"
#include "strata/objects/object_model.h"

namespace strata::apps {

/// The camera of renderModelView in the model frame: front-left, 35 degrees above the horizon, at
/// a distance that fits the bounding sphere of the model's mesh.
struct ModelCamera {
  CameraIntrinsics intrinsics;
  Eigen::Isometry3d T_M_C = Eigen::Isometry3d::Identity();
};
ModelCamera modelCamera(const objects::ObjectModel& model, int size_px);

/// Copies `tile` into `sheet` with its top-left corner at (x0, y0); the tile must fit.
void pasteTile(ColorImage& sheet, const ColorImage& tile, int x0, int y0);

/// Shaded raycast of `tsdf` (any frame F) seen by `intrinsics` at T_F_C.
ColorImage renderTsdfView(const TsdfMap& tsdf, const CameraIntrinsics& intrinsics,
                          const Eigen::Isometry3d& T_F_C);

/// A view of one model's TSDF, `size_px` square, from a fixed direction (front-left, 35 degrees
/// above the horizon) at a distance that fits its bounding sphere.
ColorImage renderModelView(const objects::ObjectModel& model, int size_px = 200);

/// Every model's view in a grid (at most 6 columns), each labelled "MODEL id" and
/// "N INSTANCES, M MERGED"; a short notice when there is none.
ColorImage renderModelSheet(const std::vector<objects::ObjectModel>& models, int size_px = 200);

}  // namespace strata::apps

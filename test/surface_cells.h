#pragma once
// Test helper for object registration: surface samples thinned to one per voxel cube, turned into
// a SurfaceCloud in the frame O at their centroid (axes as the world's, as observations are).
#include <Eigen/Geometry>
#include <map>
#include <tuple>
#include <utility>

#include "strata/objects/object_registration.h"

namespace strata::test {

/// Voxel cube (integer coordinates) -> one world-frame sample (point, normal) in it.
using SurfaceCells = std::map<std::tuple<int, int, int>, std::pair<Eigen::Vector3f, Eigen::Vector3f>>;

/// The cells' samples about their centroid, and T_W_O (a translation to the centroid).
inline std::pair<objects::SurfaceCloud, Eigen::Isometry3d> cloudAboutCentroid(
    const SurfaceCells& cells) {
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  for (const auto& [key, pn] : cells) centroid += pn.first;
  centroid /= static_cast<float>(cells.size());
  objects::SurfaceCloud cloud;
  for (const auto& [key, pn] : cells) {
    cloud.points.push_back(pn.first - centroid);
    cloud.normals.push_back(pn.second);
  }
  Eigen::Isometry3d T_W_O = Eigen::Isometry3d::Identity();
  T_W_O.translation() = centroid.cast<double>();
  return {cloud, T_W_O};
}

}  // namespace strata::test

#pragma once
// The scene items strata view and strata-view send, as wire messages (view/wire.h): meshes, object
// boxes, camera poses, trajectories, paths, ESDF slices, stats and answers. Pure functions; thread
// safe. Frames: every position is in the map's world frame W, metres; poses are T_W_C (camera to
// world, camera looking along +z).
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "strata/mesh/mesh.h"
#include "view/wire.h"

namespace strata::view {

/// A mesh: "group" is "map" (the surface), "session" (one session's own map, shown when the page
/// colours by session) or "object" (something that moved); `session` (>= 0) colours it by session
/// in the page. Colours are sent when the mesh has them. `t_pub_us` (> 0: sent as the header's
/// "t_pub_us", microseconds since the Unix epoch) is when its source published it: the page
/// measures its latency from it.
Message meshMessage(const std::string& id, const std::string& group, const Mesh& mesh,
                    int session = -1, const std::string& label = "", std::int64_t t_pub_us = 0);

struct ObjectBox {
  int id = 0;
  int session = -1;
  std::string label;
  Eigen::Vector3f min_W = Eigen::Vector3f::Zero();
  Eigen::Vector3f max_W = Eigen::Vector3f::Zero();
  std::array<std::uint8_t, 3> color{255, 210, 0};
};
Message objectsMessage(const std::vector<ObjectBox>& objects);

/// The camera `id` at T_W_C; intrinsics (width, height, fx, fy, cx, cy) shape its frustum;
/// `t_pub_us` as for meshMessage.
Message poseMessage(const std::string& id, const Eigen::Isometry3d& T_W_C, double timestamp_s,
                    const std::optional<std::array<double, 6>>& intrinsics = std::nullopt,
                    std::int64_t t_pub_us = 0);
/// A polyline (trajectory "map"/"vio", or a planned "path").
Message polylineMessage(const std::string& type, const std::string& id,
                        const std::vector<Eigen::Vector3f>& points_W);

/// An ESDF slice at height z_m: width x height cells of `resolution_m` from (origin_x, origin_y),
/// row-major from the origin's corner; NaN marks a cell of unknown distance.
struct EsdfSliceImage {
  float z_m = 0.0f;
  float origin_x_m = 0.0f, origin_y_m = 0.0f, resolution_m = 0.05f;
  int width = 0, height = 0;
  std::vector<float> distances_m;
  float max_m = 0.0f;  // colour scale top
};
Message esdfSliceMessage(const EsdfSliceImage& slice);

/// The distance at a queried point: `known` false when the ESDF has no value there.
Message answerMessage(int id, const Eigen::Vector3f& point_W, bool known, float distance_m);

}  // namespace strata::view

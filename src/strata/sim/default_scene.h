#pragma once
// The default synthetic world shared by tests and benchmarks: a small room and a camera arc.
#include <Eigen/Geometry>
#include <vector>

#include "strata/sim/analytic_scene.h"
#include "strata/sim/sensors/analytic_ray_scene.h"

namespace strata::sim {

/// A corner of a room, z up, metres: the floor half-space z < 0, two 20 cm thick walls 2.5 m high
/// along x = -2 and y = 2, and on the floor three boxes and three spheres of 30-60 cm in distinct
/// colours, all within 1.5 m of (-0.3, 0.3). Solid interiors are disjoint (objects rest on the
/// floor, walls touch at the corner), so the union SDF is exact outside and near every visible
/// surface (see analytic_scene.h).
AnalyticScene makeDefaultScene();

/// The point the default trajectory looks at, near the middle of the objects.
Eigen::Vector3d defaultSceneCentre();

/// Camera-to-world pose at `position_W` looking at `target_W`, pinhole convention: optical axis +z,
/// x right, y down (image up is world +z). Throws InputError if the view direction is vertical.
Eigen::Isometry3d lookAt(const Eigen::Vector3d& position_W, const Eigen::Vector3d& target_W);

/// `frame_count` poses on a horizontal arc of 2 m radius around defaultSceneCentre() at 1.4 m
/// height, sweeping 110 degrees from the -y side to the +x side, each looking at the centre.
/// Objects are 1.3-2.7 m away and most surfaces are seen under 60 degrees from their normal.
/// Throws InputError when frame_count < 1.
std::vector<Eigen::Isometry3d> makeDefaultTrajectory(int frame_count);

/// A closed, textured room for the stereo front end's tests and benchmarks, z up, metres: floor
/// at z = 0, ceiling at 3, walls at y = +-4 and x = +-3 (each in its own grey), and two boxes
/// (one turned 0.5 rad about z) near the wall at y = 4. `threads` as AnalyticRayScene's.
AnalyticRayScene makeStereoTestRoom(int threads);

}  // namespace strata::sim

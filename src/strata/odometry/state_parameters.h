#pragma once
// How one keyframe's state lives in Ceres: two parameter blocks.
//   pose[7]        = q_W_B (Eigen order x, y, z, w), p_W_B (m)  on PoseManifold
//   speed_bias[9]  = v_W_B (m/s), gyro bias (rad/s), accel bias (m/s^2), Euclidean
// PoseManifold is Ceres' EigenQuaternionManifold x R^3. NOTE: its rotation increment is applied on
// the left (world frame) and is half the rotation vector: q+ = [cos|d|, sin|d| d/|d|] * q.
#include <ceres/manifold.h>
#include <ceres/product_manifold.h>

namespace strata::odometry {

constexpr int kPoseSize = 7;
constexpr int kPoseTangentSize = 6;
constexpr int kSpeedBiasSize = 9;

using PoseManifold =
    ceres::ProductManifold<ceres::EigenQuaternionManifold, ceres::EuclideanManifold<3>>;

}  // namespace strata::odometry

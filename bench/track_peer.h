#pragma once
// Open3D's RGB-D odometry as the tracking peer (track_peer_open3d.cpp with STRATA_WITH_OPEN3D,
// otherwise track_peer_off.cpp reports none).
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "preload.h"

namespace strata::bench {

struct PeerTrajectory {
  bool available = false;
  std::string peer;         // name and version
  std::string method;       // what it runs, in words
  int threads = 0;
  std::vector<Eigen::Isometry3d> T_W_C;  // per frame, the first one given
  std::vector<double> ms;                // per odometry call (frames 1..n-1)
  std::size_t failures = 0;              // calls that reported failure (pose kept as before)
};

/// Chains frame-to-frame odometry from the first frame's dataset pose.
PeerTrajectory runPeerOdometry(const PreloadedFrames& data);

}  // namespace strata::bench

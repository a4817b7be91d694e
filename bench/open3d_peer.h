#pragma once
// Open3D as a peer: its tensor VoxelBlockGrid TSDF integration on the CPU over the same preloaded
// frames, poses, intrinsics and map parameters as the Strata run, and the Chamfer distance
// between the two meshes. Built only with -DSTRATA_WITH_OPEN3D=ON (open3d_peer.cpp); otherwise
// open3d_peer_off.cpp makes no peer.
#include <memory>

#include "fuse_runs.h"
#include "json.h"
#include "strata/map/map_config.h"
#include "preload.h"

namespace strata::bench {

class Open3dPeer {
 public:
  virtual ~Open3dPeer() = default;
  /// {"peer", "threads", "differences"}: what runs and how its method differs from Strata's.
  virtual Json describe() const = 0;
  /// Fuses every frame at `config`'s voxel size and compares with the Strata device run.
  virtual Json run(const MapConfig& config, const DeviceRun& strata) = 0;
};

/// Converts the frames to Open3D images (not timed). nullptr when built without Open3D.
std::unique_ptr<Open3dPeer> makeOpen3dPeer(const PreloadedFrames& data);

}  // namespace strata::bench

// Built without -DSTRATA_WITH_OPEN3D=ON: there is no Open3D peer.
#include "open3d_peer.h"

namespace strata::bench {

std::unique_ptr<Open3dPeer> makeOpen3dPeer(const PreloadedFrames& /*data*/) { return nullptr; }

}  // namespace strata::bench

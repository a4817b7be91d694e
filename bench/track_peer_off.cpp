#include "track_peer.h"

namespace strata::bench {

PeerTrajectory runPeerOdometry(const PreloadedFrames&) { return {}; }

}  // namespace strata::bench

#pragma once
// One timed replay of pre-rendered frames through LCM into an in-process mapper (lcm_command.h).
#include <cstdint>
#include <string>
#include <vector>

#include "mapper_node/mapper_options.h"
#include "strata/core/types.h"
#include "json.h"
#include "strata/vk/vk.h"

namespace strata::bench {

struct LcmRunSettings {
  std::string url;
  apps::MapperOptions mapper;
  std::string depth_encoding;
  /// Frames sent but not yet in a received mesh update: 1 measures latency without queueing,
  /// more lets receiving and decoding overlap fusion (throughput).
  int window = 1;
};

struct LcmRun {
  int window = 0;
  std::size_t frames_sent = 0;
  std::size_t frames_meshed = 0;  // frames whose mesh update arrived
  std::int64_t frames_fused = 0, frames_dropped = 0;
  double seconds = 0.0;
  std::vector<double> latency_ms;  // per frame: publish -> mesh update received
  double frame_bytes = 0.0;        // encoded rgbd_frame_t
  double mesh_update_bytes = 0.0;  // mean encoded mesh_update_t
  double fuse_ms_mean = 0.0;       // the mapper's fusion wall time per frame
};

LcmRun runLcm(vk::Context& context, const std::vector<RgbdFrame>& frames,
              const CameraIntrinsics& intrinsics, const LcmRunSettings& settings);

Json lcmRunJson(const LcmRun& run);

}  // namespace strata::bench

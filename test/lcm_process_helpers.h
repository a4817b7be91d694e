#pragma once
// Helpers of the cross-process LCM tests: the namespace replay script, LCM logs written and read,
// strata-mapper started as a child process.
#include <sys/types.h>

#include <cstdint>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "strata/core/types.h"
#include "strata/command_t.hpp"
#include "strata/esdf_slice_t.hpp"
#include "strata/map_stats_t.hpp"
#include "strata/mesh_update_t.hpp"
#include "test_utils.h"  // readText

namespace strata::test {

std::filesystem::path freshTestDir(const std::string& name);

/// Why processes cannot talk over multicast in a network namespace of their own here, so that
/// no traffic can leave the machine ("" when they can): 'unshare --net' refused (it needs root or
/// CAP_SYS_ADMIN), or no lcm-logger to record what they publish.
std::string namespaceUnavailable();

/// The first lines of a script for `unshare --net bash -c` (no single quotes): loopback up with
/// multicast routed to it (exit 10 otherwise), lcm-logger recording the channels matching the
/// regex `channels` to dir/outputs.lcm in the background, its pid in $LOGGER.
std::string namespacePrologue(const std::filesystem::path& dir, const std::string& channels);

/// Bash (no single quotes) for `unshare --net bash -c`: loopback up, multicast routed to it,
/// lcm-logger recording the mapper's outputs to dir/outputs.lcm, strata-mapper (map saved to
/// dir/map.strata on SIGTERM), strata-play of `frames` frames of the room's session 0 as fast as
/// the mapper fuses, then SIGTERM to the mapper; exit codes to dir/rc.txt, logs beside them.
std::string namespaceReplayScript(const std::filesystem::path& dir, int frames);

struct RecordedOutputs {
  std::vector<mesh_update_t> mesh_updates;
  std::vector<map_stats_t> stats;
  std::vector<esdf_slice_t> esdf_slices;
  std::size_t keyframe_scores = 0;
};
RecordedOutputs readRecordedOutputs(const std::filesystem::path& log);

/// Writes an LCM log for the file:// provider: camera info, frames and commands on the mapper's
/// channels, stamped from the moment it was opened.
class FrameLogWriter {
 public:
  FrameLogWriter(const std::filesystem::path& path, const CameraIntrinsics& intrinsics);
  /// Frame number `index`, `offset_s` after the log's start.
  void frame(const RgbdFrame& frame, int index, double offset_s);
  void command(std::int8_t command, std::int64_t request_id, double offset_s);

 private:
  template <typename Message>
  void write(const std::string& channel, std::int64_t utime, const Message& message);

  lcm::LogFile log_;
  std::int64_t t0_utime_;
};

/// An LCM log of camera info and `frames` RGB-D frames (the room's first frames, repeated),
/// `period_s` apart, for the file:// provider.
void writeFrameLog(const std::filesystem::path& path, int frames, double period_s);

/// Starts `program` with `args`, stdout and stderr to `log`; returns its pid (-1 on failure).
pid_t spawnProgram(const std::string& program, const std::vector<std::string>& args,
                   const std::filesystem::path& log);
/// spawnProgram of strata-mapper.
pid_t spawnMapper(const std::vector<std::string>& args, const std::filesystem::path& log);

struct MapperSummary {
  long long received = -1;
  long long fused = -1;
};
/// The numbers of strata-mapper's closing summary line.
MapperSummary parseMapperSummary(const std::string& log);

}  // namespace strata::test

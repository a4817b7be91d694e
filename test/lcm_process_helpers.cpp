#include "lcm_process_helpers.h"

#include <fcntl.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <sstream>
#include <unordered_map>

#include "strata/lcm/channels.h"
#include "strata/lcm/convert_frame.h"
#include "strata/lcm/convert_pose.h"
#include "strata/lcm/lcm_time.h"
#include "lcm_test_helpers.h"
#include "strata/map/block_index.h"

namespace strata::test {

namespace fs = std::filesystem;

fs::path freshTestDir(const std::string& name) {
  // The process id keeps two test runs on one machine (two build trees) out of each other's way.
  const fs::path dir =
      fs::temp_directory_path() / ("strata_test_lcm_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string namespaceUnavailable() {
  if (std::system("unshare --net true > /dev/null 2>&1") != 0) {
    return "network namespaces are not permitted here ('unshare --net' failed: needs root or "
           "CAP_SYS_ADMIN); the cross-process LCM tests run only inside a namespace of their own "
           "so that no traffic can leave the machine";
  }
  if (std::system("command -v lcm-logger > /dev/null 2>&1") != 0) {
    return "lcm-logger not found (Debian: apt-get install liblcm-bin)";
  }
  return "";
}

std::string namespacePrologue(const fs::path& dir, const std::string& channels) {
  const std::string d = dir.string();
  std::ostringstream s;
  s << "ip link set lo up && ip route add 224.0.0.0/4 dev lo || exit 10\n"
    << "lcm-logger -q -f -c \"" << channels << "\" --lcm-url=\"" << lcm_io::kDefaultUrl << "\" "
    << d << "/outputs.lcm > " << d << "/logger.log 2>&1 &\n"
    << "LOGGER=$!\n";
  return s.str();
}

std::string namespaceReplayScript(const fs::path& dir, int frames) {
  const std::string d = dir.string();
  const std::string url = lcm_io::kDefaultUrl;
  std::ostringstream s;
  s << namespacePrologue(
           dir, "STRATA_MESH_UPDATE|STRATA_MAP_STATS|STRATA_ESDF_SLICE|STRATA_KEYFRAME_SCORE")
    << STRATA_MAPPER_BIN << " --url \"" << url << "\" --map " << d
    << "/map.strata --no-change --mesh-rate 0 --esdf-rate 2 > " << d << "/mapper.log 2>&1 &\n"
    << "MAPPER=$!\n"
    << STRATA_PLAY_BIN << " sim:room:0 --sim-frames " << frames << " --rate 0 --quiet --url \""
    << url << "\" --mapper-timeout 60 > " << d << "/play.log 2>&1\n"
    << "PLAY=$?\n"
    << "kill -TERM $MAPPER; wait $MAPPER; MAPPER_RC=$?\n"
    << "sleep 0.5; kill -INT $LOGGER; wait $LOGGER\n"
    << "echo play=$PLAY mapper=$MAPPER_RC > " << d << "/rc.txt\n";
  return s.str();
}

RecordedOutputs readRecordedOutputs(const fs::path& path) {
  RecordedOutputs out;
  lcm::LogFile log(path.string(), "r");
  if (!log.good()) return out;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    if (event->channel == lcm_io::kMeshChannel) {
      mesh_update_t update;
      if (update.decode(event->data, 0, event->datalen) > 0) out.mesh_updates.push_back(update);
    } else if (event->channel == lcm_io::kStatsChannel) {
      map_stats_t stats;
      if (stats.decode(event->data, 0, event->datalen) > 0) out.stats.push_back(stats);
    } else if (event->channel == lcm_io::kEsdfChannel) {
      esdf_slice_t slice;
      if (slice.decode(event->data, 0, event->datalen) > 0) out.esdf_slices.push_back(slice);
    } else if (event->channel == lcm_io::kKeyframeChannel) {
      ++out.keyframe_scores;
    }
  }
  return out;
}

FrameLogWriter::FrameLogWriter(const fs::path& path, const CameraIntrinsics& intrinsics)
    : log_(path.string(), "w"), t0_utime_(lcm_io::nowUtime()) {
  write(lcm_io::kCameraInfoChannel, t0_utime_,
        lcm_io::encodeCameraInfo(intrinsics, "depth", t0_utime_));
}

template <typename Message>
void FrameLogWriter::write(const std::string& channel, std::int64_t utime, const Message& message) {
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(message.getEncodedSize()));
  message.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  lcm::LogEvent event{};
  event.timestamp = utime;
  event.channel = channel;
  event.datalen = static_cast<std::int32_t>(bytes.size());
  event.data = bytes.data();
  log_.writeEvent(&event);
}

void FrameLogWriter::frame(const RgbdFrame& frame, int index, double offset_s) {
  const std::int64_t utime = t0_utime_ + 1000 + static_cast<std::int64_t>(offset_s * 1e6);
  write(lcm_io::kRgbdChannel, utime,
        lcm_io::encodeFrame(frame, utime, "depth", index, lcm_io::FrameEncoding{}));
}

void FrameLogWriter::command(std::int8_t command, std::int64_t request_id, double offset_s) {
  command_t message{};
  message.utime = t0_utime_ + 1000 + static_cast<std::int64_t>(offset_s * 1e6);
  message.request_id = request_id;
  message.command = command;
  write(lcm_io::kCommandChannel, message.utime, message);
}

void writeFrameLog(const fs::path& path, int frames, double period_s) {
  const auto session = roomSession(0, 5);
  FrameLogWriter log(path, session->intrinsics());
  for (int i = 0; i < frames; ++i) {
    log.frame(session->load(static_cast<std::size_t>(i) % session->size()), i, i * period_s);
  }
}

pid_t spawnProgram(const std::string& program, const std::vector<std::string>& args,
                   const fs::path& log) {
  const pid_t pid = fork();
  if (pid != 0) return pid;
  const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  dup2(fd, STDOUT_FILENO);
  dup2(fd, STDERR_FILENO);
  std::vector<char*> argv;
  std::string name = program;
  argv.push_back(name.data());
  std::vector<std::string> copies = args;
  for (std::string& a : copies) argv.push_back(a.data());
  argv.push_back(nullptr);
  execv(name.c_str(), argv.data());
  std::perror(("execv " + program).c_str());
  _exit(127);
}

pid_t spawnMapper(const std::vector<std::string>& args, const fs::path& log) {
  return spawnProgram(STRATA_MAPPER_BIN, args, log);
}

MapperSummary parseMapperSummary(const std::string& log) {
  MapperSummary summary;
  const std::size_t at = log.find("strata-mapper: received ");
  if (at == std::string::npos) return summary;
  std::sscanf(log.c_str() + at, "strata-mapper: received %lld frames, fused %lld",
              &summary.received, &summary.fused);
  return summary;
}

}  // namespace strata::test

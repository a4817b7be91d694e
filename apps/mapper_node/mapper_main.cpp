// strata-mapper: the LCM mapping process. Subscribes frames, poses, camera infos and commands;
// fuses on the device; publishes mesh updates, ESDF slices, map stats and change events; saves
// the map on command and on SIGINT/SIGTERM. An existing --map file is loaded at start, so a
// mapper killed and restarted continues from its last saved map.
#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "cli/option_checks.h"
#include "mapper_node/mapper_core.h"
#include "mapper_node/mapper_node.h"
#include "strata/core/error.h"
#include "strata/lcm/stop_signal.h"
#include "strata/map/map_file.h"
#include "strata/vk/vk.h"

namespace {

/// What the map file holds, in words for the resume line.
std::string describe(const strata::MapFileContents& contents) {
  if (!contents.sessions) return "a plain map";
  const strata::MapSessionRecord& r = *contents.sessions;
  std::string text = std::to_string(r.sessions_ended) + " ended session" +
                     (r.sessions_ended == 1 ? "" : "s");
  if (r.session_open) {
    text += " and session " + std::to_string(r.sessions_ended) + " open with " +
            std::to_string(r.session_frames) + " frames";
  }
  return text + ", " + std::to_string(r.frames) + " frames in all";
}

/// The map to continue: --map's file when it exists. A file that does not load (torn, wrong
/// checksum, other version) or that these options cannot continue is refused with InputError and
/// left as it is: the mapper must not overwrite the only copy of a map someone may still recover.
std::optional<strata::MapFileContents> resumeMap(const strata::apps::MapperOptions& options) {
  const std::string& path = options.map_path;
  std::error_code error;
  if (path.empty() || !std::filesystem::exists(path, error)) {
    if (!path.empty()) std::fprintf(stderr, "strata-mapper: no map at %s yet: starting empty\n",
                                    path.c_str());
    return std::nullopt;
  }
  const std::string refused =
      "cannot resume from the map file (left untouched; move it away to start an empty map): ";
  try {
    strata::MapFileContents contents = strata::loadMapFile(path);
    if (!options.change_detection && contents.sessions && contents.sessions->session_open) {
      throw strata::InputError("map file '" + path +
                               "' holds a change-detection session still open (its map is that "
                               "session's observations only): continue it without --no-change");
    }
    const float voxel_m = contents.map.config().voxel_size_m;
    std::string role;
    if (options.change_detection && !contents.sessions) {
      role = "; change detection: it is the static map of an ended session";
    }
    std::fprintf(stderr, "strata-mapper: resuming from %s (%s; %zu blocks, %.3f m voxels%s)%s\n",
                 path.c_str(), describe(contents).c_str(), contents.map.blockCount(), voxel_m,
                 voxel_m != options.map.voxel_size_m ? ", the file's, not --voxel-size" : "",
                 role.c_str());
    return contents;
  } catch (const strata::InputError& e) {
    throw strata::InputError(refused + e.what());
  }
}

int runMapper(const strata::apps::MapperOptions& options, const std::atomic<bool>& stop) {
  using namespace strata;
  options.validate();
  const std::optional<MapFileContents> start = resumeMap(options);  // before the device
  // The LCM URLs too: a bad one is refused before the device starts (MapperNode names it).
  lcm::LCM input(options.url);
  std::unique_ptr<lcm::LCM> separate_output;
  if (!options.output_url.empty()) separate_output = std::make_unique<lcm::LCM>(options.output_url);
  if (!input.good()) throw InputError("LCM input '" + options.url + "' could not be opened");
  if (separate_output && !separate_output->good()) {
    throw InputError("LCM output '" + options.output_url + "' could not be opened");
  }
  vk::ContextOptions context_options;
  context_options.device_selector = options.device;
  auto context = vk::Context::create(context_options);
  apps::MapperCore core(*context, options, start ? &*start : nullptr);
  apps::MapperNode node(input, separate_output ? *separate_output : input, core, options);
  std::fprintf(stderr,
               "strata-mapper: listening on %s (frames %s, poses %s, camera info %s, commands "
               "%s); %.3f m voxels on %s; Ctrl-C saves the map to %s\n",
               options.url.c_str(), options.channels.rgbd.c_str(), options.channels.pose.c_str(),
               options.channels.camera_info.c_str(), options.channels.command.c_str(),
               options.map.voxel_size_m, context->deviceName().c_str(),
               options.map_path.empty() ? "(nowhere: --map '')" : options.map_path.c_str());
  const bool saved = node.run(stop);
  const apps::MapperCounters c = node.counters();
  std::printf(
      "strata-mapper: received %lld frames, fused %lld (%.1f ms each on average), dropped %lld "
      "behind the fusion queue and %lld without a pose, rejected %lld; %lld bad messages; %u "
      "blocks.%s\n",
      static_cast<long long>(c.frames_received), static_cast<long long>(core.framesFused()),
      core.meanFuseMs(), static_cast<long long>(c.frames_dropped_backlog),
      static_cast<long long>(c.frames_dropped_no_pose), static_cast<long long>(c.frames_rejected),
      static_cast<long long>(c.messages_bad), core.blocks(),
      saved ? "" : " The map could NOT be saved (see above).");
  return saved ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "strata-mapper: fuse RGB-D frames received over LCM, publish meshes, ESDF slices, "
      "stats and change events"};
  strata::apps::MapperOptions options;
  strata::apps::addMapperOptions(app, options);
  int exit_code = 0;
  if (!strata::apps::parseCommandLine(app, argc, argv, &exit_code)) return exit_code;
  const std::atomic<bool>& stop = strata::lcm_io::installStopSignals();
  try {
    return runMapper(options, stop);
  } catch (const strata::InputError& e) {
    std::fprintf(stderr, "strata-mapper: input error: %s\n", e.what());
    return 2;
  } catch (const strata::DeviceError& e) {
    std::fprintf(stderr, "strata-mapper: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-mapper: error: %s\n", e.what());
    return 1;
  }
}

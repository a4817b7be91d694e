#include "soak_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "chart.h"
#include "strata/core/error.h"
#include "strata/io/tum_writer.h"
#include "strata/lcm/channels.h"
#include "machine_info.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world.h"
#include "strata/sim/world/world_paths.h"
#include "soak_chart.h"
#include "soak_report.h"
#include "strata/vk/vk.h"

namespace strata::bench {
namespace {

namespace fs = std::filesystem;

// strata-mapper as it runs by default (change detection, keyframe scores, mesh at 2 Hz, ESDF at
// 1 Hz), except that it never writes its map: the soak measures memory, not the disk.
const std::vector<std::string> kMapperArgs = {"--map", ""};
// Frames written 1/30 s apart: the sessions keep a few frames spread over the whole trajectory
// (stamps ~0.8 s apart), and strata-play stamps frames now + the recording's offsets, so a
// full-speed replay would stamp ahead of the clock and the next session's first frames would
// arrive out of order (rejected by the mapper).
constexpr double kFramePeriodS = 1.0 / 30.0;

void validate(const SoakBenchOptions& o) {
  if (!(o.minutes > 0.0)) throw InputError("--minutes must be > 0");
  if (o.sessions < 1 || o.sessions > 5) throw InputError("--sessions must be 1 to 5 (the room's)");
  if (o.frames_per_session < 2) throw InputError("--frames-per-session must be at least 2");
  for (const std::string& bin : {o.mapper_bin, o.play_bin}) {
    if (!fs::exists(bin)) throw InputError("no executable at " + bin);
  }
}

/// The room's sessions 0..n-1 as TUM folders under `dir`, rendered once (noise on).
std::vector<std::string> renderSessions(const SoakBenchOptions& o, const fs::path& dir) {
  const auto world = std::make_shared<const sim::World>(sim::World::load(sim::findWorld("room")));
  sim::SimSessionConfig config;
  config.max_frames = o.frames_per_session;
  std::vector<std::string> dirs;
  for (int session = 0; session < o.sessions; ++session) {
    std::fprintf(stderr, "strata-bench soak: rendering session %d\n", session);
    const sim::SimSessionDataset data(world, session, config);
    std::vector<RgbdFrame> frames;
    for (std::size_t i = 0; i < data.size(); ++i) {
      frames.push_back(data.load(i));
      frames.back().timestamp_s = static_cast<double>(i + 1) * kFramePeriodS;
    }
    dirs.push_back((dir / ("room_" + std::to_string(session))).string());
    writeTumDataset(dirs.back(), data.intrinsics(), frames);
  }
  return dirs;
}

/// The device strata-mapper will pick, for the machine header.
std::string deviceName(const std::string& selector) {
  vk::ContextOptions options;
  options.device_selector = selector;
  options.log_device = false;
  return vk::Context::create(options)->deviceName();
}

Json settingsJson(const SoakBenchOptions& o, const SoakSettings& s) {
  std::string mapper_line = "strata-mapper --url " + s.url;
  for (const std::string& a : s.mapper_args) mapper_line += " " + (a.empty() ? "''" : a);
  return Json::object()
      .set("minutes", o.minutes)
      .set("scene", "room world, sessions 0.." + std::to_string(o.sessions - 1) +
                        " (synthetic, noise on), replayed in turn")
      .set("frames_per_session", o.frames_per_session)
      .set("processes",
           "strata-mapper and strata-play as child processes, in a private "
           "network namespace (unshare), udpm:// on its loopback")
      .set("mapper", mapper_line)
      .set("player",
           "strata-play DIR --rate 0 --quiet --url URL (flow control, window 2; "
           "ends its session after the last frame)")
      .set("sample_period_s", s.sample_period_s)
      .set("memory",
           "VmRSS/VmHWM of /proc/<strata-mapper>/status; device: map_stats_t."
           "device_bytes (Vulkan buffers the mapper's context holds)");
}

int runChecked(const SoakBenchOptions& o) {
  validate(o);
  const std::string load = loadAverage();
  const fs::path dir(o.out_dir);
  fs::create_directories(dir);
  SoakSettings s;
  s.duration_s = 60.0 * o.minutes;
  s.url = lcm_io::kDefaultUrl;
  s.mapper_bin = o.mapper_bin;
  s.play_bin = o.play_bin;
  s.mapper_args = kMapperArgs;
  if (!o.device.empty()) s.mapper_args.insert(s.mapper_args.end(), {"--device", o.device});
  s.session_dirs = renderSessions(o, dir / "sessions");
  s.frames_per_session = o.frames_per_session;
  s.log_dir = dir.string();
  const std::string device = deviceName(o.device);
  std::fprintf(stderr, "strata-bench soak: %.1f min of sessions into strata-mapper\n", o.minutes);
  const SoakRun run = runSoak(s);
  const SoakSeries series = soakSeries(run);
  const PlateauVerdict verdict = plateauVerdict(series, run.first_loop_end_s);
  writeChartPng(drawSoakChart(series, run.session_ends_s), (dir / "soak.png").string());
  Json report = Json::object().set("benchmark", "soak").set("settings", settingsJson(o, s));
  report.set("results", soakResults(run, verdict)).set("machine", machineInfo(device, load));
  emitReport(report, (dir / "soak.json").string());
  std::fprintf(stderr, "strata-bench soak: %s\n", describeSoak(run, verdict).c_str());
  return run.play_failures == 0 && run.mapper_exit_code == 0 ? 0 : 1;
}

}  // namespace

CLI::App* addSoakCommand(CLI::App& app, SoakBenchOptions& o) {
  CLI::App* soak = app.add_subcommand(
      "soak", "strata-mapper fed sessions for minutes: memory sampled each second, plateau");
  soak->add_option("--minutes", o.minutes, "How long to keep starting sessions")
      ->capture_default_str();
  soak->add_option("--sessions", o.sessions, "Room sessions replayed in turn (1-5)")
      ->capture_default_str();
  soak->add_option("--frames-per-session", o.frames_per_session, "Frames of each session")
      ->capture_default_str();
  soak->add_option("--out", o.out_dir, "Folder for soak.json, soak.png, logs, sessions")
      ->capture_default_str();
  soak->add_option("--mapper-bin", o.mapper_bin, "strata-mapper to run")->capture_default_str();
  soak->add_option("--play-bin", o.play_bin, "strata-play to run")->capture_default_str();
  soak->add_option("--device", o.device, "Vulkan device index or name substring");
  return soak;
}

int runSoakBench(const SoakBenchOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench soak: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata-bench soak: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench soak: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

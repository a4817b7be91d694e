#include "cli/select_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>
#include <vector>

#include "strata/core/progress.h"
#include "cli/select_outputs.h"
#include "cli/option_checks.h"
#include "cli/run_outputs.h"
#include "cli/select_plot.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/io/open_dataset.h"
#include "strata/mapper/mapper.h"
#include "strata/map/map_file.h"
#include "strata/select/keyframe_scorer.h"

namespace strata::apps {
namespace {

using Clock = std::chrono::steady_clock;

struct Scored {
  std::vector<ScoredKeyframe> keyframes;
  double device_ms = 0.0;
};

std::size_t frameCount(const Dataset& dataset, int frames) {
  return frames > 0 ? std::min<std::size_t>(dataset.size(), frames) : dataset.size();
}

Scored scoreDataset(Mapper& mapper, const Dataset& dataset, int frames, const std::string& label,
                    bool quiet) {
  Scored out;
  const std::size_t n = frameCount(dataset, frames);
  ProgressBar progress(label, n, !quiet);
  for (std::size_t i = 0; i < n; ++i) {
    const RgbdFrame frame = dataset.load(i);
    const KeyframeDecision decision = mapper.scoreKeyframe(frame, dataset.intrinsics());
    ScoredKeyframe k;
    k.name = frame.name;
    k.timestamp_s = frame.timestamp_s;
    k.score = decision.score;
    if (!frame.color.empty()) k.thumbnail = thumbnail(frame.color);
    out.device_ms += decision.device_ms;
    out.keyframes.push_back(std::move(k));
    progress.update(i + 1);
  }
  progress.finish();
  return out;
}

std::vector<selection::KeyframeScore> scoresOf(const Scored& s) {
  std::vector<selection::KeyframeScore> out;
  for (const auto& k : s.keyframes) out.push_back(k.score);
  return out;
}

selection::SelectionConfig selectionConfig(const SelectOptions& o) {
  selection::SelectionConfig c;
  c.method = selection::parseMethod(o.method);
  c.smoothing_window = o.window;
  c.dilation = o.dilation;
  c.thresholds.coverage = o.coverage_threshold;
  c.thresholds.color_change = o.change_threshold;
  c.thresholds.depth_change_m = o.depth_threshold_m;
  c.thresholds.surface_change = o.surface_threshold;
  c.thresholds.ncc = o.ncc_threshold;
  c.thresholds.histogram = o.hist_threshold;
  c.validate();
  return c;
}

std::string summary(const SelectOptions& o, const Scored& scored,
                    const selection::TrajectorySelection& s, const selection::SelectionConfig& c,
                    const std::vector<std::string>& files, double wall_s) {
  const std::size_t n = scored.keyframes.size();
  std::ostringstream out;
  out.precision(3);
  out << "strata select: " << s.selectedCount() << " of " << n << " keyframes of " << o.session_dir
      << " selected by '" << selection::methodName(c.method) << "' against " << o.map_path << " ("
      << (o.calibrate_dir.empty() ? "given" : "automatic") << " thresholds: coverage < "
      << c.thresholds.coverage << ", colour change > " << c.thresholds.color_change
      << ", depth change > " << c.thresholds.depth_change_m << " m, surface change > "
      << c.thresholds.surface_change << ", ncc < " << c.thresholds.ncc << ", hist < "
      << c.thresholds.histogram << "; window " << c.smoothing_window << ", dilation " << c.dilation
      << ", every " << o.stride_px << " px). Raycast device time "
      << scored.device_ms / std::max<std::size_t>(n, 1) << " ms per keyframe, " << wall_s
      << " s in all. Wrote " << o.out_dir << "/keyframes.csv";
  for (const auto& f : files) out << ", " << f;
  out << ".";
  return out.str();
}

const std::vector<std::string> kFiles = {"keyframes.csv", "selection.png", "selected.png"};
constexpr int kMaxStridePx = 4096;

/// Every option, before any file is read: InputError naming the option and what it accepts.
void checkOptions(const SelectOptions& o) {
  if (o.map_path.empty()) throw InputError("a map file (.strata) is required");
  if (o.session_dir.empty()) throw InputError("a session folder is required");
  if (o.out_dir.empty()) throw InputError("--out DIR must not be empty");
  if (o.method != "reproj" && o.method != "ncc" && o.method != "hist") {
    throw InputError("--method: unknown method '" + o.method + "' (choose reproj, ncc or hist)");
  }
  requireCount(o.stride_px, "--stride", 1, kMaxStridePx);
  if (o.window < 1 || o.window % 2 == 0) {
    throw InputError("--window (the smoothing_window) must be odd and >= 1, not " +
                     std::to_string(o.window));
  }
  requireCount(o.dilation, "--dilation", 0, std::numeric_limits<int>::max());
  requireCount(o.frames, "--frames", 0, std::numeric_limits<int>::max());
  for (const auto& [option, value] :
       {std::pair{"--coverage-threshold", o.coverage_threshold},
        std::pair{"--change-threshold", o.change_threshold},
        std::pair{"--depth-threshold", o.depth_threshold_m},
        std::pair{"--surface-threshold", o.surface_threshold},
        std::pair{"--ncc-threshold", o.ncc_threshold},
        std::pair{"--hist-threshold", o.hist_threshold}}) {
    if (!std::isfinite(value)) {
      throw InputError(std::string(option) + " must be a finite number, not " +
                       std::to_string(value));
    }
  }
}

/// The map and the sessions against --out and its files, before anything is read or made.
void checkPaths(const SelectOptions& o) {
  for (const auto& [what, dir] : {std::pair{"session folder", o.session_dir},
                                  std::pair{"--calibrate: session folder", o.calibrate_dir}}) {
    if (!dir.empty() && !std::filesystem::is_directory(dir)) {
      throw InputError(std::string(what) + " '" + dir + "' " +
                       (std::filesystem::exists(dir) ? "is a file, not a folder"
                                                     : "does not exist"));
    }
  }
  OutputPaths paths;
  paths.inputFile(o.map_path, "the map");
  paths.inputFolder(o.session_dir, "the session");
  paths.inputFolder(o.calibrate_dir, "--calibrate");
  outputFolderFiles(paths, o.out_dir, "--out", kFiles);
  paths.check();
}

int runChecked(const SelectOptions& o) {
  const auto start = Clock::now();
  checkOptions(o);
  selection::SelectionConfig config = selectionConfig(o);
  checkPaths(o);
  const TsdfMap host_map = loadMap(o.map_path);
  const std::unique_ptr<Dataset> session = openDataset(o.session_dir);
  std::unique_ptr<Dataset> calibration;
  if (!o.calibrate_dir.empty()) calibration = openDataset(o.calibrate_dir);
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  const auto context = vk::Context::create(context_options);
  MapperConfig mapper_config;
  mapper_config.map = host_map.config();
  mapper_config.keyframe_scoring = true;
  mapper_config.scorer.sample_stride_px = o.stride_px;
  // The trajectory decision below (smoothing, dilation) is this program's; the Mapper's own
  // per-frame decision is not used.
  const std::unique_ptr<Mapper> mapper = Mapper::fromMap(host_map, *context, mapper_config);
  if (calibration) {
    const Scored own = scoreDataset(*mapper, *calibration, o.frames, "calibrate", o.quiet);
    config.thresholds = selection::autoThresholds(scoresOf(own), o.window, config.thresholds);
  }
  const Scored scored = scoreDataset(*mapper, *session, o.frames, "score keyframes", o.quiet);
  const selection::TrajectorySelection s = selection::selectKeyframes(scoresOf(scored), config);
  // A failed write leaves none of the files (nor the folder when this run made it).
  OutputCleanup cleanup;
  cleanup.folder(o.out_dir, kFiles);
  std::filesystem::create_directories(o.out_dir);
  writeSelectionCsv((std::filesystem::path(o.out_dir) / "keyframes.csv").string(), scored.keyframes,
                    s);
  const auto files = writeSelectionPictures(o.out_dir, scored.keyframes, s, config);
  cleanup.keep();
  const double wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("%s\n", summary(o, scored, s, config, files, wall_s).c_str());
  return 0;
}

}  // namespace

CLI::App* addSelectCommand(CLI::App& app, SelectOptions& o) {
  CLI::App* c = app.add_subcommand(
      "select", "Select the keyframes of a new session worth reconstructing against a map");
  c->add_option("map", o.map_path, "Map file (strata fuse --map)")->required();
  c->add_option("session", o.session_dir, "Session folder (TUM RGB-D or 7-Scenes layout)")
      ->required();
  c->add_option("--out", o.out_dir, "Output folder")->capture_default_str();
  c->add_option("--method", o.method, "reproj (raycast reprojection) | ncc | hist")
      ->capture_default_str()
      ->check(CLI::IsMember({"reproj", "ncc", "hist"}));
  c->add_option("--calibrate", o.calibrate_dir,
                "Session the map was built from: automatic thresholds from its own frames");
  c->add_option("--stride", o.stride_px, "Sample every n-th pixel")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxStridePx));
  c->add_option("--window", o.window, "Moving-average window, keyframes (odd)")
      ->capture_default_str()
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  c->add_option("--dilation", o.dilation, "Keyframes added on each side of a selected one")
      ->capture_default_str()
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  c->add_option("--coverage-threshold", o.coverage_threshold, "Select below this coverage")
      ->capture_default_str()
      ->check(finiteNumber());
  c->add_option("--change-threshold", o.change_threshold, "Select above this colour change")
      ->capture_default_str()
      ->check(finiteNumber());
  c->add_option("--depth-threshold", o.depth_threshold_m,
                "Select above this depth change, metres (negative: unused)")
      ->capture_default_str()
      ->check(finiteNumber());
  c->add_option("--surface-threshold", o.surface_threshold,
                "Select above this share of measured samples the map does not hold (negative: "
                "unused; kept under --calibrate)")
      ->capture_default_str()
      ->check(finiteNumber());
  c->add_option("--ncc-threshold", o.ncc_threshold, "ncc: select below")
      ->capture_default_str()
      ->check(finiteNumber());
  c->add_option("--hist-threshold", o.hist_threshold, "hist: select below")
      ->capture_default_str()
      ->check(finiteNumber());
  c->add_option("--frames", o.frames, "Score only the first n frames (0: all)")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  c->add_option("--device", o.device, "Vulkan device index or name substring");
  c->add_flag("--quiet", o.quiet, "No progress bar");
  return c;
}

int runSelect(const SelectOptions& o) {
  try {
    return runChecked(o);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata select: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata select: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata select: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps

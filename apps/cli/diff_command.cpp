#include "cli/diff_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <vector>

#include "cli/diff_outputs.h"
#include "strata/mapper/session_diff.h"
#include "cli/diff_report.h"
#include "cli/option_checks.h"
#include "cli/run_outputs.h"
#include "strata/change/change_config.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/io/open_dataset.h"
#include "strata/map/map_file.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

/// Every `stride`-th frame of a dataset, at most `limit` of them (0: no limit).
class FrameSelection : public Dataset {
 public:
  FrameSelection(std::unique_ptr<Dataset> inner, int stride, int limit)
      : inner_(std::move(inner)), stride_(static_cast<std::size_t>(stride)) {
    count_ = (inner_->size() + stride_ - 1) / stride_;
    if (limit > 0) count_ = std::min(count_, static_cast<std::size_t>(limit));
  }
  std::string name() const override { return inner_->name(); }
  std::size_t size() const override { return count_; }
  CameraIntrinsics intrinsics() const override { return inner_->intrinsics(); }
  RgbdFrame load(std::size_t index) const override { return inner_->load(index * stride_); }

 private:
  std::unique_ptr<Dataset> inner_;
  std::size_t stride_;
  std::size_t count_ = 0;
};

/// One session as given: frames from a folder, or a saved map.
struct SessionInput {
  std::string path;
  std::unique_ptr<Dataset> frames;
  std::unique_ptr<TsdfMap> map;
};

/// The dataset options of session `index`: with --trajectory, its poses from that file.
DatasetOptions sessionDatasetOptions(const DiffOptions& o, std::size_t index) {
  DatasetOptions options = o.dataset_options;
  if (o.trajectories.empty()) return options;
  if (fs::is_regular_file(o.sessions[index])) {
    throw InputError("session '" + o.sessions[index] +
                     "' is a saved map; --trajectory applies to session folders only");
  }
  options.trajectory_file = o.trajectories[index];
  return options;
}

// The files in --out: diff_outputs.h's and the report.
const std::vector<std::string> kFiles = {"static_mesh.ply", "report.json"};
const std::vector<std::string> kFilePatterns = {"static_mesh.ply", "report.json", "session_*"};

/// Every option, before any file is read: InputError naming the option and what it accepts.
void checkOptions(const DiffOptions& o) {
  for (const std::string& path : o.sessions) {
    if (!fs::exists(path)) throw InputError("session '" + path + "' does not exist");
  }
  if (o.sessions.size() < 2) throw InputError("diff needs at least two sessions to compare");
  if (!o.trajectories.empty() && o.trajectories.size() != o.sessions.size()) {
    throw InputError("--trajectory given " + std::to_string(o.trajectories.size()) +
                     " time(s) for " + std::to_string(o.sessions.size()) +
                     " sessions: give one per session, in order, or none");
  }
  for (const std::string& path : o.sessions) {
    if (!o.trajectories.empty() && fs::is_regular_file(path)) {
      throw InputError("session '" + path +
                       "' is a saved map; --trajectory applies to session folders only");
    }
  }
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  requireNumberIn(o.voxel_size_m, "--voxel-size", "metres", 0.001, 1.0);  // MapConfig's range
  if (o.weight != "constant" && o.weight != "inv-z2") {
    throw InputError("--weight: unknown weight '" + o.weight + "' (choose constant or inv-z2)");
  }
  requireNumber(o.min_weight, "--min-weight", "recorded frames", 0.0, false);
  // Above change detection's merge distance (ChangeConfig::merge_close_m).
  const float merge_close_m = change::ChangeConfig{}.merge_close_m;
  requireNumber(o.difference_threshold_m, "--threshold", "metres", merge_close_m, false);
  requireCount(o.frames, "--frames", 0, std::numeric_limits<int>::max());
  requireCount(o.stride, "--stride", 1, std::numeric_limits<int>::max());
  const std::string& format = o.dataset_options.format;
  if (format != "auto" && format != "tum" && format != "7scenes") {
    throw InputError("--format: unknown layout '" + format + "' (choose auto, tum or 7scenes)");
  }
}

/// The sessions, trajectories and camera file against --out and its files, before anything is
/// read or made.
void checkPaths(const DiffOptions& o) {
  OutputPaths paths;
  for (const std::string& path : o.sessions) {
    if (fs::is_directory(path)) {
      paths.inputFolder(path, "the session");
    } else {
      paths.inputFile(path, "the saved map");
    }
  }
  for (const std::string& path : o.trajectories) paths.inputFile(path, "--trajectory");
  paths.inputFile(o.dataset_options.camera_file, "--camera");
  outputFolderFiles(paths, o.out_dir, "--out", kFiles);
  paths.check();
}

/// "'PATH' (voxel size 0.02 m, truncation 0.08 m)".
std::string describeGrid(const std::string& path, const MapConfig& c) {
  char text[120];
  std::snprintf(text, sizeof(text), " (voxel size %g m, truncation %g m)",
                static_cast<double>(c.voxel_size_m), static_cast<double>(c.truncationDistance()));
  return "'" + path + "'" + text;
}

/// Opens every session before any work, so a bad path fails at once, naming it; saved maps must
/// share one voxel grid (the first's), or the layers would not compare voxel for voxel.
std::vector<SessionInput> openSessions(const DiffOptions& o) {
  std::vector<SessionInput> inputs;
  inputs.reserve(o.sessions.size());  // first_map points into it
  const SessionInput* first_map = nullptr;
  for (std::size_t i = 0; i < o.sessions.size(); ++i) {
    const std::string& path = o.sessions[i];
    SessionInput input{path, nullptr, nullptr};
    const DatasetOptions options = sessionDatasetOptions(o, i);
    if (fs::is_regular_file(path)) {
      input.map = std::make_unique<TsdfMap>(loadMap(path));
      if (first_map) {
        const MapConfig& a = first_map->map->config();
        const MapConfig& b = input.map->config();
        if (std::fabs(a.voxel_size_m - b.voxel_size_m) > 1e-7f ||
            std::fabs(a.truncationDistance() - b.truncationDistance()) > 1e-7f) {
          throw InputError("the saved maps " + describeGrid(first_map->path, a) + " and " +
                           describeGrid(path, b) +
                           " have different voxel grids: saved maps must share one to be "
                           "compared");
        }
      }
    } else {
      input.frames =
          std::make_unique<FrameSelection>(openDataset(path, options), o.stride, o.frames);
    }
    inputs.push_back(std::move(input));
    if (!first_map && inputs.back().map) first_map = &inputs.back();
  }
  return inputs;
}

/// The first saved map's grid when there is one (layers must agree voxel for voxel), else the
/// options'.
MapConfig mapConfigFor(const DiffOptions& o, const std::vector<SessionInput>& inputs) {
  for (const SessionInput& input : inputs) {
    if (input.map) return input.map->config();
  }
  MapConfig config = change::changeMapConfig(o.voxel_size_m);
  config.weight_mode =
      o.weight == "inv-z2" ? WeightMode::kInverseDepthSquared : WeightMode::kConstant;
  return config;
}

void runChecked(const DiffOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  checkOptions(o);
  checkPaths(o);
  std::vector<SessionInput> inputs = openSessions(o);
  DiffRunInfo info;
  info.change.min_weight = o.min_weight;
  // --min-weight counts recorded frames; every stride-th frame stands for `stride` of them.
  info.change = info.change.forSubsampling(o.stride);
  info.change.difference_threshold_m = o.difference_threshold_m;
  const MapConfig map_config = mapConfigFor(o, inputs);
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  const auto context = vk::Context::create(context_options);
  info.device = context->deviceName();
  info.map_config = map_config.describe();
  DiffPipeline pipeline(*context, map_config, info.change, info.objects);
  std::size_t total = 0, done = 0;
  for (const SessionInput& input : inputs) total += input.frames ? input.frames->size() : 0;
  ProgressBar progress("diff: fuse sessions", total, !o.quiet);
  for (const SessionInput& input : inputs) {
    if (input.map) {
      pipeline.addSessionMap(*input.map, input.path);
    } else {
      pipeline.addSession(*input.frames, input.path, progress, done);
    }
  }
  progress.finish();
  if (!o.quiet) std::fprintf(stderr, "diff: meshing and discovering objects...\n");
  const DiffResult result = pipeline.finish();
  // The folder only now, with the results: a failed write leaves none of the files (nor the
  // folder when this run made it).
  OutputCleanup cleanup;
  cleanup.folder(o.out_dir, kFilePatterns);
  fs::create_directories(o.out_dir);
  const DiffFiles files = writeDiffFiles(result, o.out_dir);
  info.total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeDiffReport((fs::path(o.out_dir) / "report.json").string(), result, files, info);
  cleanup.keep();
  std::printf("%s\n", summarizeDiff(result, info, o.out_dir).c_str());
}

}  // namespace

CLI::App* addDiffCommand(CLI::App& app, DiffOptions& o) {
  CLI::App* diff = app.add_subcommand(
      "diff", "Multi-session change detection: static map, moved objects per session");
  diff->add_option("sessions", o.sessions,
                   "Session folders (TUM RGB-D / 7-Scenes, e.g. from `strata sim`) or saved "
                   ".strata maps, oldest first")
      ->required();
  diff->add_option("--out", o.out_dir, "Output folder")->required();
  diff->add_option("--trajectory", o.trajectories,
                   "TUM trajectory replacing a session folder's groundtruth.txt (e.g. aligned "
                   "odometry); repeat once per session, in order")
      ->allow_extra_args(false)
      ->take_all();
  diff->add_option("--voxel-size", o.voxel_size_m,
                   "Voxel edge, metres, 0.001 to 1 (saved maps keep theirs)")
      ->capture_default_str()
      ->check(finiteNumber());
  diff->add_option("--weight", o.weight,
                   "Observation weight: constant (min weight counts frames) | inv-z2")
      ->check(CLI::IsMember({"constant", "inv-z2"}))
      ->capture_default_str();
  diff->add_option("--min-weight", o.min_weight,
                   "Weight below which a voxel is unobserved (constant weights: recorded frames "
                   "that saw it; divided by --stride)")
      ->capture_default_str()
      ->check(finiteNumber());
  diff->add_option("--threshold", o.difference_threshold_m,
                   "Distance change that labels a voxel dynamic, metres")
      ->capture_default_str()
      ->check(finiteNumber());
  diff->add_option("--frames", o.frames, "Fuse at most N frames per session (0: all)")
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  diff->add_option("--stride", o.stride, "Use every N-th frame")
      ->check(CLI::Range(1, std::numeric_limits<int>::max()));
  diff->add_option("--device", o.device, "Vulkan device index or name substring");
  diff->add_option("--format", o.dataset_options.format, "Dataset layout: auto | tum | 7scenes")
      ->check(CLI::IsMember({"auto", "tum", "7scenes"}));
  diff->add_option("--camera", o.dataset_options.camera_file, "Camera YAML for every session");
  diff->add_flag("--quiet", o.quiet, "No progress bar");
  return diff;
}

int runDiff(const DiffOptions& o) {
  try {
    runChecked(o);
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata diff: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata diff: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata diff: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps

#include "cli/objects_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <vector>

#include "strata/mapper/session_diff.h"
#include "cli/objects_before_after.h"
#include "cli/objects_outputs.h"
#include "cli/objects_truth.h"
#include "cli/option_checks.h"
#include "cli/run_outputs.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/io/image_io.h"
#include "strata/io/open_dataset.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

/// Every `stride`-th frame of a dataset.
class EveryNthFrame : public Dataset {
 public:
  EveryNthFrame(std::unique_ptr<Dataset> inner, std::size_t stride)
      : inner_(std::move(inner)), stride_(stride) {}
  std::string name() const override { return inner_->name(); }
  std::size_t size() const override { return (inner_->size() + stride_ - 1) / stride_; }
  CameraIntrinsics intrinsics() const override { return inner_->intrinsics(); }
  RgbdFrame load(std::size_t index) const override { return inner_->load(index * stride_); }

 private:
  std::unique_ptr<Dataset> inner_;
  std::size_t stride_;
};

// The files in --out: objects_outputs.h's.
const std::vector<std::string> kFiles = {"objects.json", "objects.sodb", "objects.png"};
const std::vector<std::string> kFilePatterns = {"objects.json", "objects.sodb", "objects.png",
                                                "model_*", "session_*"};

/// Every option, before any file is read: InputError naming the option and what it accepts.
void checkOptions(const ObjectsOptions& o) {
  for (const std::string& path : o.sessions) {
    if (!fs::is_directory(path)) {
      throw InputError("session '" + path + "' is not a folder (" +
                       (fs::exists(path) ? "a file" : "it does not exist") + ")");
    }
  }
  if (o.sessions.size() < 2) {
    throw InputError("objects needs at least two sessions (objects are found where they moved)");
  }
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  requireNumberIn(o.voxel_size_m, "--voxel", "metres", 0.001, 1.0);  // MapConfig's range
  requireCount(o.frames, "--frames", 0, std::numeric_limits<int>::max());
  requireNumber(o.min_weight, "--min-weight", "recorded frames", 0.0, false);
}

fs::path normalPath(const std::string& path) {
  fs::path p = fs::absolute(path).lexically_normal();
  return p.filename().empty() ? p.parent_path() : p;
}

/// The sessions and the world file against --out, its files and --before-after, before anything
/// is read or made.
void checkPaths(const ObjectsOptions& o) {
  OutputPaths paths;
  for (const std::string& path : o.sessions) paths.inputFolder(path, "the session");
  if (!o.world.empty() && fs::exists(o.world)) paths.inputFile(o.world, "--world");
  outputFolderFiles(paths, o.out_dir, "--out", kFiles);
  if (!o.before_after_png.empty()) {
    const fs::path picture = normalPath(o.before_after_png);
    const std::string name = picture.filename().string();
    const bool in_out = picture.parent_path() == normalPath(o.out_dir);
    // In --out its name must not be one the other files there take (model_K.ply,
    // session_K_completed.ply among them, which no list holds before the run).
    if (in_out && (std::find(kFiles.begin(), kFiles.end(), name) != kFiles.end() ||
                   name.rfind("model_", 0) == 0 || name.rfind("session_", 0) == 0)) {
      throw InputError("--before-after '" + o.before_after_png +
                       "' is a name the files in --out use: choose another path");
    }
    // A new --out is made before the picture is written: nothing of it to check yet.
    if (!in_out || fs::is_directory(o.out_dir)) {
      paths.outputFile(o.before_after_png, "--before-after");
    }
  }
  paths.check();
}

/// Opens every session before any work, so a bad folder fails at once, naming it.
std::vector<std::unique_ptr<Dataset>> openSessions(const ObjectsOptions& o) {
  std::vector<std::unique_ptr<Dataset>> sessions;
  for (const std::string& path : o.sessions) sessions.push_back(openDataset(path, {}));
  return sessions;
}

/// The stride that spreads about `frames` frames over the longest session.
std::size_t strideFor(const std::vector<std::unique_ptr<Dataset>>& sessions, int frames) {
  std::size_t longest = 0;
  for (const auto& s : sessions) longest = std::max(longest, s->size());
  if (frames <= 0 || longest <= static_cast<std::size_t>(frames)) return 1;
  return (longest + static_cast<std::size_t>(frames) - 1) / static_cast<std::size_t>(frames);
}

void runChecked(const ObjectsOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  checkOptions(o);
  checkPaths(o);
  std::vector<std::unique_ptr<Dataset>> inputs = openSessions(o);
  std::string why_not;
  const auto truth = findSimTruth(o.sessions, o.world, why_not);
  const std::size_t stride = strideFor(inputs, o.frames);
  change::ChangeConfig change_config;
  change_config.min_weight = o.min_weight;
  change_config = change_config.forSubsampling(static_cast<int>(stride));
  const MapConfig map_config = change::changeMapConfig(o.voxel_size_m);
  vk::ContextOptions context_options;
  context_options.device_selector = o.device;
  const auto context = vk::Context::create(context_options);
  DiffPipeline pipeline(*context, map_config, change_config, change::ObjectConfig{});
  std::vector<std::unique_ptr<Dataset>> sessions;
  std::size_t total = 0, done = 0;
  for (auto& input : inputs) {
    sessions.push_back(std::make_unique<EveryNthFrame>(std::move(input), stride));
    total += sessions.back()->size();
  }
  ProgressBar progress("objects: fuse sessions", total, !o.quiet);
  for (std::size_t i = 0; i < sessions.size(); ++i) {
    pipeline.addSession(*sessions[i], o.sessions[i], progress, done);
  }
  progress.finish();
  if (!o.quiet) std::fprintf(stderr, "objects: discovering and matching objects...\n");
  std::vector<TsdfMap> maps;
  const DiffResult result = pipeline.finish(&maps);
  const ObjectsRun run = buildObjectDatabase(result, maps);
  std::string truth_json, truth_summary = "no truth: " + why_not;
  if (truth) {
    const eval::ObjectDbEvaluation e = evaluateObjectsRun(*truth, result, run);
    truth_json = eval::objectDbEvaluationJson(e);
    truth_summary = "against the truth of world '" + truth->world->name() +
                    "': " + eval::describeObjectDbEvaluation(e);
  }
  // A failed write leaves none of the files (nor the folder when this run made it).
  OutputCleanup cleanup;
  cleanup.folder(o.out_dir, kFilePatterns);
  cleanup.file(o.before_after_png);
  fs::create_directories(o.out_dir);
  const ObjectsFiles files = writeObjectsFiles(run, result, o.out_dir, truth_json);
  if (!o.before_after_png.empty()) {
    writeColorPng(o.before_after_png, renderBeforeAfter(run, result, maps));
  }
  cleanup.keep();
  const double total_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf(
      "Object database over %zu sessions (%zu frames each at most, %.0f s): %s; %s. "
      "Wrote %s, %zu model meshes, %s and %s.\n",
      result.sessions.size(), sessions.front()->size(), total_s, summarizeObjects(run).c_str(),
      truth_summary.c_str(), files.json.c_str(), files.models.size(), files.database.c_str(),
      files.contact_sheet.c_str());
}

}  // namespace

CLI::App* addObjectsCommand(CLI::App& app, ObjectsOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "objects", "Object database over sessions: moved objects matched, merged into models");
  cmd->add_option("sessions", o.sessions,
                  "Session folders (TUM RGB-D, e.g. from `strata sim`), oldest first")
      ->required();
  cmd->add_option("--out", o.out_dir, "Output folder")->required();
  cmd->add_option("--voxel", o.voxel_size_m, "Voxel edge, metres (0.001 to 1)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--frames", o.frames, "Frames per session, spread over it (0: all)")
      ->capture_default_str()
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  cmd->add_option("--min-weight", o.min_weight,
                  "Recorded frames a voxel must be seen in to count as observed (> 0)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--world", o.world,
                  "World file of the sessions' ground truth (default: the name it records)");
  cmd->add_option("--device", o.device, "Vulkan device index or name substring");
  cmd->add_flag("--quiet", o.quiet, "No progress bar");
  cmd->add_option("--before-after", o.before_after_png,
                  "Also write a PNG of the most merged models: largest single view above the "
                  "merged model");
  return cmd;
}

int runObjects(const ObjectsOptions& o) {
  try {
    runChecked(o);
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata objects: input error: %s\n", e.what());
    return 2;
  } catch (const DeviceError& e) {
    std::fprintf(stderr, "strata objects: device error: %s\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata objects: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps

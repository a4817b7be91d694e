#include "cli/localize_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <vector>

#include "cli/option_checks.h"
#include "cli/report_json.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/core/pose_interpolation.h"
#include "strata/core/progress.h"
#include "strata/core/statistics.h"
#include "strata/io/open_dataset.h"
#include "strata/io/tum_format.h"
#include "strata/localize/session_localization.h"
#include "strata/store/session_store.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;
constexpr int kMaxEvery = 100000;
constexpr int kMaxThreads = 1024;
constexpr double kWrongTranslation_m = 0.5;  // a placed frame this far off is wrong
constexpr double kWrongRotation_deg = 10.0;

std::string summaryPath(const LocalizeOptions& o) {
  if (!o.summary_path.empty()) return o.summary_path;
  return fs::path(o.out_path).replace_extension(".json").string();
}

std::string odometryPath(const LocalizeOptions& o) {
  if (o.no_odometry) return {};
  if (!o.odometry_path.empty()) return o.odometry_path;
  const fs::path candidate = fs::path(o.session_dir) / "odometry.txt";
  return fs::exists(candidate) ? candidate.string() : std::string();
}

void checkOptions(const LocalizeOptions& o) {
  if (!fs::is_directory(o.session_dir)) {
    throw InputError("session folder '" + o.session_dir + "' " +
                     (fs::exists(o.session_dir) ? "is a file, not a folder" : "does not exist"));
  }
  if (!fs::is_regular_file(o.db_path))
    throw InputError("--db: map database '" + o.db_path + "' does not exist");
  if (o.no_odometry && !o.odometry_path.empty())
    throw InputError("--odometry and --no-odometry contradict each other");
  if (!o.odometry_path.empty() && !fs::is_regular_file(o.odometry_path))
    throw InputError("--odometry: '" + o.odometry_path + "' does not exist");
  if (!o.truth_path.empty() && !fs::is_regular_file(o.truth_path))
    throw InputError("--truth: '" + o.truth_path + "' does not exist");
  requireCount(o.every, "--every", 1, kMaxEvery);
  requireCount(o.threads, "--threads", 1, kMaxThreads);
  OutputPaths paths;
  paths.inputFolder(o.session_dir, "the session folder");
  paths.inputFile(o.db_path, "--db");
  paths.inputFile(odometryPath(o), "--odometry");
  paths.inputFile(o.truth_path, "--truth");
  paths.outputFile(o.out_path, "--out");
  paths.outputFile(summaryPath(o), "--summary");
  paths.check();
}

struct FrameError {
  double translation_m = 0.0, rotation_deg = 0.0;
  std::optional<double> localization_m;  // of the frame's own localisation, when it had one
};

Json frameJson(const localize::FrameLocalization& f, const std::optional<FrameError>& error) {
  Json j;
  j["frame"] = f.frame;
  j["timestamp_s"] = f.timestamp_s;
  j["status"] = localize::fusionStatusName(f.fused.status);
  j["attempted"] = f.attempted;
  if (f.attempted) {
    const localize::Localization& l = f.localization;
    j["localized"] = l.localized;
    if (l.localized) {
      j["source"] = l.candidate_source;
      j["surface"] = l.from_surface;
      j["inliers"] = l.inliers;
      j["residual_m"] = l.residual_m;
      j["overlap"] = l.overlap;
    } else {
      j["reason"] = l.reason;
    }
    j["candidates"] = l.candidates;
    j["time_ms"] = l.time_ms;
    j["features_ms"] = l.features_ms;
    j["surface_ms"] = l.surface_ms;
    j["verify_ms"] = l.verify_ms;
  }
  if (!f.fused.note.empty()) j["note"] = f.fused.note;
  if (f.placed()) {
    j["sigma_m"] = f.fused.translation_sigma_m;
    j["jump_m"] = f.fused.jump_m;
  }
  if (error) {
    j["error_m"] = error->translation_m;
    j["error_deg"] = error->rotation_deg;
    if (error->localization_m) j["localization_error_m"] = *error->localization_m;
  }
  return j;
}

int run(const LocalizeOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  checkOptions(o);
  const std::string odometry_file = odometryPath(o);
  std::vector<tum::TimedPose> truth;
  if (!o.truth_path.empty()) truth = tum::readTrajectory(o.truth_path);

  store::StoreOptions store_options;
  store_options.read_only = true;
  store::Store db(o.db_path, store_options);
  localize::PriorMapConfig map_config;
  map_config.threads = o.threads;
  std::optional<ProgressBar> load_bar;
  const localize::PriorMap map = localize::PriorMap::fromStore(
      db, map_config, [&](std::size_t done, std::size_t total) {
        if (!load_bar) load_bar.emplace("loading the map", total, !o.quiet);
        load_bar->update(done);
      });
  if (load_bar) load_bar->finish();
  const double load_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  DatasetOptions options;
  options.trajectory_file = odometry_file;
  const std::unique_ptr<Dataset> frames = openDataset(o.session_dir, options);
  std::vector<Eigen::Isometry3d> odometry;
  if (!odometry_file.empty())
    for (std::size_t i = 0; i < frames->size(); ++i) odometry.push_back(frames->stamp(i).T_W_C);

  localize::SessionLocalizationConfig config;
  config.every = o.every;
  ProgressBar bar("localising", frames->size(), !o.quiet);
  const localize::SessionLocalization result = localize::localizeSession(
      *frames, odometry, map, config, [&](std::size_t done, std::size_t) {
        bar.update(done);
        return true;
      });
  bar.finish();

  std::string trajectory;
  Json per_frame = Json::array();
  std::vector<double> times_ms, errors_m, errors_deg;
  std::size_t placed = 0, wrong = 0;
  double max_jump = 0.0;
  for (const localize::FrameLocalization& f : result.frames) {
    std::optional<FrameError> error;
    if (f.placed()) {
      ++placed;
      trajectory += tum::poseToTum(f.fused.T_W_C).insert(0, std::to_string(f.timestamp_s) + " ");
      trajectory += "\n";
      max_jump = std::max(max_jump, f.fused.jump_m);
      if (!truth.empty()) {
        const std::optional<Eigen::Isometry3d> T = interpolateStamped(
            truth, f.timestamp_s, 0.1, [](const tum::TimedPose& p) { return p.timestamp_s; },
            [](const tum::TimedPose& p) { return p.T_W_C; });
        if (T) {
          const Eigen::Isometry3d d = T->inverse() * f.fused.T_W_C;
          error = FrameError{d.translation().norm(), 0.0, std::nullopt};
          error->rotation_deg =
              Eigen::AngleAxisd(d.linear()).angle() * 180.0 / M_PI;
          if (f.attempted && f.localization.localized)
            error->localization_m = (T->translation() - f.localization.T_W_C.translation()).norm();
          errors_m.push_back(error->translation_m);
          errors_deg.push_back(error->rotation_deg);
          if (error->translation_m > kWrongTranslation_m || error->rotation_deg > kWrongRotation_deg)
            ++wrong;
        }
      }
    }
    if (f.attempted) times_ms.push_back(f.localization.time_ms);
    per_frame.push_back(frameJson(f, error));
  }
  const double total_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  Json summary;
  summary["session"] = fs::absolute(o.session_dir).string();
  summary["map"] = fs::absolute(o.db_path).string();
  summary["map_sessions"] = map.sessions();
  summary["map_sessions_left_out"] = map.skipped_sessions();
  summary["map_keyframes"] = map.keyframes().size();
  summary["odometry"] = odometry_file.empty() ? Json(nullptr) : Json(odometry_file);
  summary["every"] = o.every;
  summary["frames"] = result.frames.size();
  summary["placed"] = placed;
  summary["placed_fraction"] = result.frames.empty() ? 0.0 : double(placed) / result.frames.size();
  summary["attempted"] = result.attempted;
  summary["localized"] = result.localized;
  summary["localized_fraction"] =
      result.attempted == 0 ? 0.0 : double(result.localized) / result.attempted;
  summary["accepted_by_fusion"] = result.accepted;
  summary["rejected_by_fusion"] = result.rejected;
  summary["max_jump_m"] = max_jump;
  Json timing;
  timing["map_load_s"] = load_s;
  timing["localization_median_ms"] = times_ms.empty() ? 0.0 : median(times_ms);
  timing["localization_p90_ms"] = times_ms.empty() ? 0.0 : quantile(times_ms, 0.9);
  timing["total_s"] = total_s;
  summary["timing"] = timing;
  if (!truth.empty()) {
    Json t;
    t["file"] = fs::absolute(o.truth_path).string();
    t["scored"] = errors_m.size();
    t["median_error_m"] = errors_m.empty() ? 0.0 : median(errors_m);
    t["max_error_m"] = errors_m.empty() ? 0.0 : *std::max_element(errors_m.begin(), errors_m.end());
    t["median_error_deg"] = errors_deg.empty() ? 0.0 : median(errors_deg);
    t["max_error_deg"] =
        errors_deg.empty() ? 0.0 : *std::max_element(errors_deg.begin(), errors_deg.end());
    t["wrong"] = wrong;  // > 0.5 m or 10 degrees
    summary["truth"] = t;
  }
  summary["per_frame"] = per_frame;
  const std::string summary_file = summaryPath(o);
  writeTextAtomically(o.out_path, trajectory);
  try {
    writeTextAtomically(summary_file, jsonFileText(summary));
  } catch (...) {
    std::error_code ignored;
    fs::remove(o.out_path, ignored);
    throw;
  }
  std::printf("%zu of %zu frames placed in the map frame; %zu of %zu localisations succeeded "
              "(%.1f %%), %zu rejected by the fusion; median %.0f ms per localisation\n",
              placed, result.frames.size(), result.localized, result.attempted,
              result.attempted ? 100.0 * result.localized / result.attempted : 0.0,
              result.rejected, times_ms.empty() ? 0.0 : median(times_ms));
  if (!errors_m.empty()) {
    std::printf("against %s: median error %.1f mm / %.2f deg, max %.1f mm; %zu frames off by "
                "more than 0.5 m or 10 deg\n",
                o.truth_path.c_str(), 1e3 * median(errors_m), median(errors_deg),
                1e3 * *std::max_element(errors_m.begin(), errors_m.end()), wrong);
  }
  std::printf("Wrote %s and %s\n", o.out_path.c_str(), summary_file.c_str());
  return 0;
}

}  // namespace

CLI::App* addLocalizeCommand(CLI::App& app, LocalizeOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "localize", "Localise every frame of a recorded session against a prior map database");
  cmd->add_option("session", o.session_dir, "Session folder (TUM layout)")->required();
  cmd->add_option("--db", o.db_path, "Map database (strata map import / strata align)")
      ->required();
  cmd->add_option("--out", o.out_path, "Map-frame poses of the placed frames (TUM)")->required();
  cmd->add_option("--summary", o.summary_path, "JSON summary (default: --out with .json)");
  cmd->add_option("--odometry", o.odometry_path,
                  "The session's odometry (TUM; default: its odometry.txt when present)");
  cmd->add_flag("--no-odometry", o.no_odometry, "Localise every frame on its own");
  cmd->add_option("--truth", o.truth_path, "Score the placed frames against this (TUM, map frame)");
  cmd->add_option("--every", o.every, "Localise every n-th frame (odometry in between)")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxEvery));
  cmd->add_option("--threads", o.threads, "Map loading workers")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxThreads));
  cmd->add_flag("--quiet", o.quiet, "No progress bars");
  return cmd;
}

int runLocalize(const LocalizeOptions& o) {
  try {
    return run(o);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata localize: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata localize: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps

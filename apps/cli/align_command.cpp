#include "cli/align_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <optional>
#include <vector>

#include "cli/align_outputs.h"
#include "cli/align_plot.h"
#include "cli/option_checks.h"
#include "cli/run_outputs.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/core/progress.h"
#include "strata/store/session_import.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

void importFolders(store::Store& db, const AlignOptions& o) {
  store::ImportOptions options;
  options.keyframe_every = o.keyframe_every;
  options.keyframe_distance_m = o.keyframe_distance_m;
  options.odometry_sigma_m = o.odometry_sigma_m;
  options.odometry_sigma_rad = o.odometry_sigma_rad;
  for (const std::string& dir : o.session_dirs) {
    std::optional<ProgressBar> bar;
    const auto progress = [&](std::size_t done, std::size_t total) {
      if (!bar) bar.emplace("importing " + dir, total, !o.quiet);
      bar->update(done);
    };
    const store::ImportResult r = store::importTumSession(db, dir, options, progress);
    if (bar) bar->finish();
    std::printf("%s: %s session %lld '%s' (%zu keyframes of %zu frames, odometry %s)\n",
                dir.c_str(), r.skipped ? "already in the map as" : "imported as",
                static_cast<long long>(r.session_id), r.name.c_str(), r.keyframes, r.frames,
                r.odometry_file.c_str());
  }
}

align::AlignConfig alignConfig(const AlignOptions& o) {
  align::AlignConfig config;
  config.candidates_per_keyframe = static_cast<std::size_t>(o.candidates);  // >= 1: checked
  config.min_intra_session_gap_s = o.intra_gap_s;
  config.intra_session_loops = !o.no_intra;
  config.threads = o.threads;
  config.graph.threads = o.threads;
  return config;
}

void printSummary(const align::StoreAlignment& a, const align::AlignmentScore* score) {
  for (std::size_t s = 0; s < a.sessions.size(); ++s) {
    const align::AlignedSession& r = a.result.sessions[s];
    std::printf("session %zu '%s': %zu keyframes, %s\n", s, a.sessions[s].name.c_str(),
                r.keyframes.size(),
                r.aligned ? (s == 0 ? "anchor (world frame)" : "aligned")
                          : "UNALIGNED (no verified loop joins it to the others)");
  }
  std::size_t accepted = 0;
  for (const align::AlignLoop& l : a.result.loops) accepted += l.accepted ? 1 : 0;
  std::printf("loops: %zu candidates verified, %zu passed verification, %zu kept by the graph\n",
              a.result.candidates, a.result.loops.size(), accepted);
  if (score) {
    std::printf(
        "truth: ATE %.1f mm after alignment (before: %.3f m, odometry in its own frames); loops "
        "kept %zu true / %zu false (precision %.3f), keyframe recall %.3f\n",
        1e3 * score->ate_after_rmse_m, score->ate_before_rmse_m, score->accepted_true,
        score->accepted_false, score->loop_precision, score->loop_recall);
  }
}

const std::vector<std::string> kAlignFiles = {"loops.csv", "report.json", "trajectories.png"};
constexpr int kMaxCandidates = 1000;
constexpr int kMaxThreads = 1024;

/// Every option, before any file is read or made: InputError naming the option and what it
/// accepts.
void checkOptions(const AlignOptions& o) {
  if (o.session_dirs.empty() && o.db_path.empty())
    throw InputError("give session folders (with --out) or --db map.sqlite");
  if (!o.session_dirs.empty() && o.out_dir.empty())
    throw InputError("--out DIR is needed with session folders");
  requireCount(o.keyframe_every, "--keyframe-every", 0, std::numeric_limits<int>::max());
  requireNumber(o.keyframe_distance_m, "--keyframe-distance-m", "metres; 0: off", 0.0, true);
  if (o.keyframe_every == 0 && o.keyframe_distance_m == 0.0) {
    throw InputError("--keyframe-every and --keyframe-distance-m are both 0 (off): set one");
  }
  requireNumber(o.odometry_sigma_m, "--odometry-sigma-m", "metres", 0.0, false);
  requireNumber(o.odometry_sigma_rad, "--odometry-sigma-rad", "radians", 0.0, false);
  requireCount(o.candidates, "--candidates", 1, kMaxCandidates);
  requireNumber(o.intra_gap_s, "--intra-gap-s", "seconds", 0.0, true);
  requireCount(o.threads, "--threads", 1, kMaxThreads);
  for (const std::string& dir : o.session_dirs) {
    if (!fs::is_directory(dir)) {
      throw InputError("session folder '" + dir + "' " +
                       (fs::exists(dir) ? "is a file, not a folder" : "does not exist"));
    }
  }
  if (o.session_dirs.empty() && !fs::exists(o.db_path)) {
    throw InputError("--db: map database '" + o.db_path + "' does not exist");
  }
}

fs::path normalPath(const std::string& path) {
  fs::path p = fs::absolute(path).lexically_normal();
  return p.filename().empty() ? p.parent_path() : p;
}

/// The inputs (session folders, the database when it exists) against the outputs (the folder, its
/// files, `session_count` session_K folders, a new database), before anything is made or written.
void checkPaths(const std::vector<std::string>& session_folders, const std::string& db_path,
                bool db_existed, const std::string& out_dir, std::size_t session_count) {
  OutputPaths paths;
  for (const std::string& dir : session_folders) paths.inputFolder(dir, "the session folder");
  std::vector<std::string> files = kAlignFiles;
  if (db_existed) {
    paths.inputFile(db_path, "the map database");
  } else if (normalPath(db_path).parent_path() == normalPath(out_dir)) {
    // Made in the output folder, which may not exist yet: only its name can collide.
    const std::string name = normalPath(db_path).filename().string();
    if (std::find(kAlignFiles.begin(), kAlignFiles.end(), name) != kAlignFiles.end()) {
      throw InputError("--db '" + db_path + "' is the output " + name + " of --out '" + out_dir +
                       "': choose another path");
    }
    files.push_back(name);
  } else {
    paths.outputFile(db_path, "--db");
  }
  outputFolderFiles(paths, out_dir, "--out", files);
  for (std::size_t k = 0; k < session_count; ++k) {
    paths.outputFolder((fs::path(out_dir) / ("session_" + std::to_string(k))).string(), "--out");
  }
  paths.check();
}

int run(const AlignOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  checkOptions(o);
  const std::string out_dir =
      !o.out_dir.empty() ? o.out_dir : fs::absolute(o.db_path).parent_path().string();
  const std::string db_path =
      !o.db_path.empty() ? o.db_path : (fs::path(out_dir) / "map.sqlite").string();
  const bool db_existed = fs::exists(db_path);
  checkPaths(o.session_dirs, db_path, db_existed, out_dir, o.session_dirs.size());
  // A failed run leaves no output: what it made is removed (after the database is closed), the
  // database rolled back (below).
  OutputCleanup cleanup;
  std::vector<std::string> names = kAlignFiles;
  names.push_back("session_*");
  cleanup.folder(out_dir, names);
  if (!db_existed) {
    for (const char* suffix : {"", "-wal", "-shm", "-journal"}) cleanup.file(db_path + suffix);
  }
  fs::create_directories(out_dir);
  store::StoreOptions store_options;
  store_options.create = !o.session_dirs.empty();
  store::Store db(db_path, store_options);
  {
    // The database's sessions are inputs too (their folders are read): checked before writing.
    std::vector<std::string> folders = o.session_dirs;
    const std::vector<store::SessionRecord> stored = db.sessions();
    for (const store::SessionRecord& s : stored) folders.push_back(s.source_folder);
    checkPaths(folders, db_path, true, out_dir, stored.size() + o.session_dirs.size());
  }
  // The imports, the alignment and the files are one transaction: a folder that fails to import
  // or a session that fails to align (or a file that cannot be written) leaves the database as it
  // was, so the next `align --db` does not meet a half-made session. NOTE: it holds the database's
  // write lock for the whole run (other writers wait 5 s, then fail).
  store::Transaction transaction = db.beginTransaction();
  if (!o.session_dirs.empty()) importFolders(db, o);

  std::map<std::string, std::optional<ProgressBar>> bars;
  const auto progress = [&](const std::string& stage, std::size_t done, std::size_t total) {
    auto& bar = bars[stage];
    if (!bar) bar.emplace(stage, total, !o.quiet);
    bar->update(done);
    if (done == total) bar->finish();
  };
  const align::AlignConfig config = alignConfig(o);
  const align::StoreAlignment a = align::alignStore(db, config, progress);
  std::optional<align::AlignmentScore> score;
  if (!o.no_truth) {
    if (const auto truth = align::loadStoreTruth(a)) score = align::scoreAlignment(a.result, *truth, config);
  }
  const align::AlignmentScore* score_ptr = score ? &*score : nullptr;
  const fs::path out(out_dir);
  const std::vector<std::string> written = writeAlignedTrajectories(a, out_dir);
  writeLoopsCsv(a, score_ptr, (out / "loops.csv").string());
  std::vector<std::string> session_names;
  for (const store::SessionRecord& s : a.sessions) session_names.push_back(s.name);
  writeAlignPlot((out / "trajectories.png").string(), a.result, session_names);
  const double total_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  writeAlignReport(a, score_ptr, db.path(), total_s, (out / "report.json").string());
  transaction.commit();
  cleanup.keep();
  for (const std::string& f : written) std::printf("Wrote %s\n", f.c_str());
  printSummary(a, score_ptr);
  std::printf("Wrote %s/{loops.csv,report.json,trajectories.png}; the map database %s holds the "
              "result\n", out_dir.c_str(), db.path().c_str());
  return 0;
}

}  // namespace

CLI::App* addAlignCommand(CLI::App& app, AlignOptions& o) {
  CLI::App* cmd = app.add_subcommand(
      "align", "Register sessions recorded in their own odometry frames into one map");
  cmd->add_option("sessions", o.session_dirs,
                  "Session folders (TUM layout; odometry.txt or groundtruth.txt); the first "
                  "anchors the world frame");
  cmd->add_option("--db", o.db_path, "Map database (default with folders: OUT/map.sqlite)");
  cmd->add_option("--out", o.out_dir, "Output folder (default with --db: the database's)");
  cmd->add_option("--keyframe-every", o.keyframe_every,
                  "Import: a keyframe every N frames (0: off)")
      ->capture_default_str()
      ->check(CLI::Range(0, std::numeric_limits<int>::max()));
  cmd->add_option("--keyframe-distance-m", o.keyframe_distance_m,
                  "Import: or after this much motion, metres (0: off)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--odometry-sigma-m", o.odometry_sigma_m,
                  "Import: odometry edge noise between keyframes, metres (> 0)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--odometry-sigma-rad", o.odometry_sigma_rad,
                  "Import: odometry edge noise between keyframes, radians (> 0)")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_option("--candidates", o.candidates, "Place candidates verified per keyframe")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxCandidates));
  cmd->add_option("--intra-gap-s", o.intra_gap_s,
                  "Loops within a session join keyframes at least this far apart, seconds")
      ->capture_default_str()
      ->check(finiteNumber());
  cmd->add_flag("--no-intra", o.no_intra, "No loops within a session");
  cmd->add_flag("--no-truth", o.no_truth, "Do not score against groundtruth.txt");
  cmd->add_option("--threads", o.threads, "Worker threads")
      ->capture_default_str()
      ->check(CLI::Range(1, kMaxThreads));
  cmd->add_flag("--quiet", o.quiet, "No progress bars");
  return cmd;
}

int runAlign(const AlignOptions& o) {
  try {
    return run(o);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata align: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata align: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::apps

#include "cli/map_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "cli/map_info.h"
#include "cli/run_outputs.h"
#include "strata/core/progress.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/store/session_import.h"

namespace strata::apps {

namespace {

int importInto(const MapOptions& o, const store::ImportOptions& options) {
  store::Store db(o.db_path);
  std::size_t imported = 0;
  for (const std::string& dir : o.session_dirs) {
    std::optional<ProgressBar> bar;
    const auto progress = [&](std::size_t done, std::size_t total) {
      if (!bar) bar.emplace("importing " + dir, total, !o.quiet);
      bar->update(done);
    };
    const store::ImportResult r = store::importTumSession(db, dir, options, progress);
    if (bar) bar->finish();
    if (r.skipped) {
      std::printf("%s: already in %s as session %lld '%s'; skipped\n", dir.c_str(),
                  o.db_path.c_str(), static_cast<long long>(r.session_id), r.name.c_str());
      continue;
    }
    ++imported;
    std::printf(
        "%s: session %lld '%s': %zu keyframes of %zu frames, %zu odometry edges, %zu "
        "resources (odometry from %s)\n",
        dir.c_str(), static_cast<long long>(r.session_id), r.name.c_str(), r.keyframes, r.frames,
        r.edges, r.resources, r.odometry_file.c_str());
  }
  std::printf("Imported %zu of %zu session folders into %s\n", imported, o.session_dirs.size(),
              o.db_path.c_str());
  return 0;
}

int runImport(const MapOptions& o) {
  for (const std::string& dir : o.session_dirs) {  // before the database is opened or made
    if (!std::filesystem::is_directory(dir)) {
      throw InputError("session folder '" + dir + "' does not exist or is not a folder");
    }
  }
  store::ImportOptions options;
  options.keyframe_every = o.keyframe_every;
  options.keyframe_distance_m = o.keyframe_distance_m;
  // A failed first import leaves no database behind (nor SQLite's journal files).
  OutputCleanup cleanup;
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) cleanup.file(o.db_path + suffix);
  const int code = importInto(o, options);
  cleanup.keep();
  return code;
}

int runInfo(const MapOptions& o) {
  store::StoreOptions options;
  options.read_only = true;  // a command that reads never writes
  store::Store db(o.db_path, options);
  const std::vector<store::SessionSummary> summary = db.summary();
  std::vector<store::ResourceProblem> problems;
  if (o.verify) problems = db.verifyResources();
  const std::string text = o.json ? mapInfoJson(db.path(), summary, problems, o.verify)
                                  : mapInfoTable(db.path(), summary, problems, o.verify);
  std::fputs(text.c_str(), stdout);
  return problems.empty() ? 0 : 2;
}

int runExport(const MapOptions& o) {
  OutputPaths paths;
  paths.inputFile(o.db_path, "the map database");
  paths.outputFolder(o.out_dir, "--out");
  paths.check();
  store::StoreOptions options;
  options.read_only = true;  // a command that reads never writes
  store::Store db(o.db_path, options);
  if (db.sessions().empty()) {
    throw InputError("map database '" + o.db_path + "' holds no session: nothing to export");
  }
  const std::vector<std::string> files = store::exportTrajectories(db, o.out_dir);
  for (const std::string& f : files) std::printf("Wrote %s\n", f.c_str());
  std::printf("Exported %zu sessions of %s into %s\n", db.sessions().size(), o.db_path.c_str(),
              o.out_dir.c_str());
  return 0;
}

}  // namespace

CLI::App* addMapCommand(CLI::App& app, MapOptions& o) {
  CLI::App* map = app.add_subcommand("map", "The map database of many sessions (SQLite)");
  map->require_subcommand(1);
  CLI::App* import = map->add_subcommand("import", "Import TUM-layout session folders");
  import->add_option("sessions", o.session_dirs, "Session folders (as `strata sim` writes)")
      ->required();
  import->add_option("--db", o.db_path, "Map database (created when absent)")->required();
  import->add_option("--keyframe-every", o.keyframe_every, "A keyframe every N frames (0: off)")
      ->capture_default_str();
  import
      ->add_option("--keyframe-distance-m", o.keyframe_distance_m,
                   "Or after this much motion, metres (0: off)")
      ->capture_default_str();
  import->add_flag("--quiet", o.quiet, "No progress bar");
  import->callback([&o] { o.action = "import"; });
  CLI::App* info = map->add_subcommand("info", "Sessions, counts, path lengths and time spans");
  info->add_option("--db", o.db_path, "Map database")->required();
  info->add_flag("--json", o.json, "Print JSON instead of a table");
  info->add_flag("--verify", o.verify,
                 "Check every resource's size and CRC-32 (exit 2 if any is missing or changed)");
  info->callback([&o] { o.action = "info"; });
  CLI::App* out = map->add_subcommand("export", "Each session's keyframe trajectory as TUM files");
  out->add_option("--db", o.db_path, "Map database")->required();
  out->add_option("--out", o.out_dir, "Output folder")->required();
  out->callback([&o] { o.action = "export"; });
  return map;
}

int runMap(const MapOptions& o) {
  const std::string command = "strata map " + o.action;
  try {
    if (o.action == "import") return runImport(o);
    if (o.action == "info") return runInfo(o);
    if (o.action == "export") return runExport(o);
    throw InputError("unknown map action '" + o.action + "' (import, info, export)");
  } catch (const InputError& e) {
    std::fprintf(stderr, "%s: input error: %s\n", command.c_str(), e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: error: %s\n", command.c_str(), e.what());
    return 1;
  }
}

}  // namespace strata::apps

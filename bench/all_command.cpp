#include "all_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "child_process.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "machine_info.h"
#include "suite_plots.h"

namespace strata::bench {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct Run {
  std::string name;               // file stem: DIR/<name>.json
  std::string benchmark;          // subcommand
  std::vector<std::string> args;  // after the subcommand
};

std::vector<Run> plannedRuns(const AllBenchOptions& o) {
  std::vector<std::string> fuse_args;
  if (o.fuse_frames > 0) fuse_args = {"--frames", std::to_string(o.fuse_frames)};
  std::vector<Run> runs = {{"fuse", "fuse", fuse_args}};
  for (const int prefill : o.map_size_prefill) {
    std::vector<std::string> args = fuse_args;
    args.insert(args.end(), {"--voxel-sizes", "0.02", "--reference-frames", "0",
                             "--prefill-blocks", std::to_string(prefill)});
    runs.push_back({"fuse_prefill_" + std::to_string(prefill), "fuse", args});
  }
  for (const char* name : {"esdf", "diff", "select", "sim", "lcm", "occupancy", "objects", "plan",
                           "plan-collision", "explore-gain"}) {
    runs.push_back({name, name, {}});
  }
  return runs;
}

bool selected(const AllBenchOptions& o, const Run& run) {
  if (o.only.empty()) return true;
  for (const std::string& name : o.only) {
    if (name == run.benchmark || name == run.name) return true;
  }
  return false;
}

/// Runs this executable with `args`, stdout to /dev/null (the report goes to --out), stderr
/// shared so progress shows. Returns the exit code (128 + signal when killed).
int runChild(const std::vector<std::string>& args) {
  return waitProcess(spawnProcess(selfExecutable(), args, "/dev/null"));
}

json readReport(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return json();
  try {
    return json::parse(in);
  } catch (const json::parse_error& e) {
    std::fprintf(stderr, "strata-bench all: %s is not valid JSON: %s\n", path.c_str(), e.what());
    return json();
  }
}

std::string commandLine(const Run& run) {
  std::string line = "strata-bench " + run.benchmark;
  for (const std::string& a : run.args) line += " " + a;
  return line;
}

std::vector<std::string> writePlots(const json& fuse, const std::vector<json>& map_size,
                                    const fs::path& dir) {
  std::vector<std::string> written;
  const auto put = [&](const cv::Mat& image, const std::string& name) {
    writeChartPng(image, (dir / name).string());
    written.push_back(name);
  };
  if (!fuse.is_null()) {
    put(drawBarChart(fuseKernelChart(fuse)), "fuse_kernels.png");
    put(drawBarChart(ceilingChart(fuse)), "fuse_ceiling.png");
  }
  if (!map_size.empty()) put(drawLineChart(mapSizeChart(map_size, 0.02)), "fuse_map_size.png");
  return written;
}

int runChecked(const AllBenchOptions& o) {
  if (o.out_dir.empty()) throw InputError("--out DIR is required");
  for (const int prefill : o.map_size_prefill) {
    if (prefill < 0) throw InputError("--map-size-prefill values must be >= 0");
  }
  const fs::path dir(o.out_dir);
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw InputError("cannot create " + o.out_dir + ": " + ec.message());
  const std::string load_at_start = loadAverage();
  json runs = json::array();
  json fuse;
  std::vector<json> map_size;
  bool all_ok = true;
  for (const Run& run : plannedRuns(o)) {
    if (!selected(o, run)) continue;
    const fs::path report_path = dir / (run.name + ".json");
    std::vector<std::string> args = {run.benchmark};
    args.insert(args.end(), run.args.begin(), run.args.end());
    args.insert(args.end(), {"--out", report_path.string()});
    // The simulator, the object database's matching and the graph planners run on the host.
    const bool host_only =
        run.benchmark == "sim" || run.benchmark == "objects" || run.benchmark == "plan";
    if (!o.device.empty() && !host_only) args.insert(args.end(), {"--device", o.device});
    std::fprintf(stderr, "strata-bench all: %s\n", commandLine(run).c_str());
    fs::remove(report_path, ec);  // a stale report must not pass for this run's
    const auto start = std::chrono::steady_clock::now();
    const int code = runChild(args);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    json report = readReport(report_path);
    all_ok = all_ok && code == 0 && !report.is_null();
    if (run.benchmark == "fuse" && !report.is_null()) {
      if (run.name == "fuse") fuse = report;
      map_size.push_back(report);
    }
    runs.push_back({{"name", run.name},
                    {"command", commandLine(run)},
                    {"exit_code", code},
                    {"seconds", seconds},
                    {"report", report}});
  }
  const std::vector<std::string> plots = writePlots(fuse, map_size, dir);
  json all = {{"benchmark", "all"},
              {"machine", json::parse(machineInfo("see each report", load_at_start).dump())},
              {"runs", runs},
              {"plots", plots},
              {"all_passed", all_ok}};
  writeTextAtomically(dir / "all.json", all.dump(2) + "\n");
  std::ostringstream md;
  md << "# strata-bench all\n\n| benchmark | command | exit | seconds |\n|---|---|---|---|\n";
  for (const json& r : runs) {
    md << "| " << r["name"].get<std::string>() << " | `" << r["command"].get<std::string>()
       << "` | " << r["exit_code"].get<int>() << " | " << r["seconds"].get<double>() << " |\n";
  }
  if (!fuse.is_null()) md << "\n## Fusion (medians)\n\n" << fuseMarkdownTable(fuse);
  writeTextAtomically(dir / "summary.md", md.str());
  std::fprintf(stderr, "strata-bench all: wrote %s/all.json, summary.md and %zu plots%s\n",
               o.out_dir.c_str(), plots.size(), all_ok ? "" : " (a benchmark failed)");
  std::printf("%s\n", all.dump(2).c_str());
  return all_ok ? 0 : 1;
}

}  // namespace

CLI::App* addAllCommand(CLI::App& app, AllBenchOptions& o) {
  CLI::App* all = app.add_subcommand(
      "all", "Every benchmark into one JSON, plus PNG plots and a markdown summary");
  all->add_option("--out", o.out_dir, "Output folder (created when missing)")->required();
  all->add_option("--only", o.only, "Run only these (fuse, esdf, diff, select, sim, lcm, "
                                    "occupancy, fuse_prefill_N)")
      ->delimiter(',');
  all->add_option("--map-size-prefill", o.map_size_prefill,
                  "Extra 2 cm fuse runs with this many far blocks preloaded")
      ->delimiter(',')
      ->capture_default_str();
  all->add_option("--fuse-frames", o.fuse_frames, "Frames for the fuse runs (0: all)")
      ->capture_default_str();
  all->add_option("--device", o.device, "Vulkan device index or name substring");
  return all;
}

int runAllBench(const AllBenchOptions& options) {
  try {
    return runChecked(options);
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench all: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench all: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

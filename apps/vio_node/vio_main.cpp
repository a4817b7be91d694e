// strata-vio: visual-inertial odometry over LCM. Subscribes grey stereo (or mono) frames and IMU
// samples, runs the VIO pipeline with the calibration of an EuRoC session folder, and publishes
// T_W_C of cam0 for every tracked frame at the frame's own stamp (strata-mapper interpolates
// its RGB-D frames' poses from them). Bad input is counted and skipped; a progress line goes to
// stderr every few seconds, a JSON summary to --summary at exit (SIGINT/SIGTERM, or --max-idle-s
// after the streams stop). Exit codes: 0; 2 bad input (options, calibration, --summary's path,
// before listening); 3 frames came and none was tracked.
#include <CLI/CLI.hpp>
#include <atomic>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/option_checks.h"
#include "strata/core/atomic_file.h"
#include "strata/core/error.h"
#include "strata/core/output_paths.h"
#include "strata/io/euroc_dataset.h"
#include "strata/lcm/stop_signal.h"
#include "strata/odometry/solver_log.h"
#include "vio_node/vio_node.h"

namespace {

void describeCalibration(const strata::euroc::Calibration& c, const strata::apps::VioOptions& o) {
  const strata::euroc::CameraCalibration& left = c.cameras.at(0);
  std::fprintf(stderr,
               "strata-vio: listening on %s (frames %s, IMU %s), poses T_W_C of %s on %s; %s "
               "%dx%d from %s\n",
               o.url.c_str(), o.channels.stereo.c_str(), o.channels.imu.c_str(), left.name.c_str(),
               o.channels.pose.c_str(), c.stereo() && !o.pipeline.mono ? "stereo" : "mono",
               left.width_px, left.height_px, o.calib_dir.c_str());
}

int runVio(const strata::apps::VioOptions& options, const std::atomic<bool>& stop) {
  using namespace strata;
  options.validate();
  OutputPaths paths;
  paths.inputFolder(options.calib_dir, "--calib");
  paths.outputFile(options.summary_path, "--summary");
  paths.check();
  const euroc::Calibration calibration =
      euroc::readCalibration(options.calib_dir, !options.pipeline.mono);
  lcm::LCM input(options.url);
  std::unique_ptr<lcm::LCM> separate_output;
  if (!options.output_url.empty()) separate_output = std::make_unique<lcm::LCM>(options.output_url);
  apps::VioNode node(input, separate_output ? *separate_output : input, calibration, options);
  describeCalibration(calibration, options);
  const odometry::SolverLog& solver =
      odometry::SolverLog::install("strata-vio", options.solver_log);
  const apps::VioSnapshot s = node.run(stop);
  if (!solver.summary().empty()) {
    std::fprintf(stderr, "strata-vio: %s\n", solver.summary().c_str());
  }
  if (!options.summary_path.empty()) {
    const std::string json = apps::vioSummaryJson(s, options.calib_dir);
    writeFileAtomically(options.summary_path, std::vector<std::uint8_t>(json.begin(), json.end()));
  }
  std::printf(
      "strata-vio: stopped by %s after %.1f s: %lld frames received, %zu tracked, %zu "
      "failures, %lld poses published.\n",
      s.stopped_by.c_str(), s.elapsed_s, static_cast<long long>(s.counters.frames_received),
      s.pipeline.frames_tracking, s.pipeline.failures,
      static_cast<long long>(s.counters.poses_published));
  std::string message;
  const int code = apps::vioVerdict(s, &message);
  std::fputs(message.c_str(), stderr);
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "strata-vio: visual-inertial odometry on grey stereo + IMU received over LCM; publishes "
      "camera poses for strata-mapper"};
  strata::apps::VioOptions options;
  strata::apps::addVioOptions(app, options);
  int exit_code = 0;
  if (!strata::apps::parseCommandLine(app, argc, argv, &exit_code)) return exit_code;
  const std::atomic<bool>& stop = strata::lcm_io::installStopSignals();
  try {
    return runVio(options, stop);
  } catch (const strata::InputError& e) {
    std::fprintf(stderr, "strata-vio: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-vio: error: %s\n", e.what());
    return 1;
  }
}

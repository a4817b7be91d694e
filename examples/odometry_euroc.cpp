// Visual-inertial odometry (grey stereo, or mono, + IMU) over an EuRoC/ASL session folder with
// strata::odometry: prints each status change and about one pose per second, and writes the left
// camera's trajectory in the TUM format.   odometry_euroc SESSION_DIR [OUT.txt] [MAX_FRAMES]
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "strata/io/euroc_dataset.h"
#include "strata/io/tum_writer.h"
#include "strata/odometry/pipeline/vio_replay.h"

namespace odo = strata::odometry;

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: odometry_euroc SESSION_DIR [OUT.txt] [MAX_FRAMES]\n");
    return 2;
  }
  const std::string out = argc > 2 ? argv[2] : "trajectory.txt";
  try {
    const auto dataset = strata::euroc::EurocDataset::open(argv[1]);  // folder holding mav0/
    odo::VioPipeline pipeline(dataset.calibration(), odo::VioPipelineConfig{});
    odo::ReplayInput input;  // IMU and frames merged in time order, images loaded when pushed
    input.imu = &dataset.imu();
    for (const auto& frame : dataset.frames())
      input.frame_timestamps_ns.push_back(frame.timestamp_ns);
    input.load = [&](std::size_t k) { return dataset.loadImages(k); };
    input.max_frames = argc > 3 ? std::strtoul(argv[3], nullptr, 10) : 0;
    odo::VioStatus status = odo::VioStatus::kInitializing;
    std::int64_t last_printed_ns = 0;
    input.on_processed = [&](const odo::PipelineFrame& f) {
      const double t_s = 1e-9 * static_cast<double>(f.timestamp_ns);
      if (f.status != status) {
        std::printf("%.3f s: %s %s\n", t_s, odo::toString(f.status), f.reason.c_str());
        status = f.status;
      }
      if (f.status == odo::VioStatus::kTracking &&
          f.timestamp_ns - last_printed_ns >= 1'000'000'000) {
        const Eigen::Vector3d p = f.T_W_C.translation();
        std::printf("%.3f s: camera at (%.3f, %.3f, %.3f) m, %d landmarks\n", t_s, p.x(), p.y(),
                    p.z(), f.landmarks);
        last_printed_ns = f.timestamp_ns;
      }
    };
    const odo::ReplayResult result = odo::replayVio(pipeline, input);
    std::vector<strata::tum::TimedPose> poses;
    for (const odo::PipelineFrame& f : result.tracked)
      poses.push_back({1e-9 * static_cast<double>(f.timestamp_ns), f.T_W_C});
    strata::writeTumTrajectory(out, poses,
                               {"timestamp tx ty tz qx qy qz qw (left camera to world)"});
    std::printf("%s VIO: %zu of %zu frames tracked, %zu failures, %.1f s -> %s\n",
                result.stereo ? "stereo" : "mono", result.stats.frames_tracking,
                result.stats.frames_processed, result.stats.failures, result.wall_s, out.c_str());
    return result.tracked.empty() ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "odometry_euroc: %s\n", e.what());
    return 1;
  }
}

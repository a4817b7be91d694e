#pragma once
// `strata-bench frontend`: speed of the visual front end (odometry/frontend) per stereo frame, on
// a simulated 752x480 stereo sequence and on the EuRoC V1_01 excerpt when it is present.
#include <string>

namespace CLI {
class App;
}

namespace strata::bench {

struct FrontendBenchOptions {
  int frames = 60;         // simulated stereo frames timed (after the first, which only detects)
  int threads = 2;         // OpenCV threads (cv::setNumThreads); the VIO's budget is 2 cores
  std::string euroc_mav0;  // EuRoC mav0 folder; "" = ../shared/data/euroc_v101_micro/mav0
  std::string out_path;
};

CLI::App* addFrontendCommand(CLI::App& app, FrontendBenchOptions& options);
int runFrontendBench(const FrontendBenchOptions& options);

}  // namespace strata::bench

#include "frontend_command.h"

#include <time.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

#include "strata/core/error.h"
#include "strata/core/statistics.h"
#include "json.h"
#include "machine_info.h"
#include "strata/odometry/frontend/feature_tracker.h"
#include "strata/sim/default_scene.h"
#include "strata/sim/sensors/analytic_ray_scene.h"
#include "strata/sim/sensors/grey_camera.h"

namespace strata::bench {
namespace {

using odometry::FrameFeatures;

// Fixed scene (sim::makeStereoTestRoom, shared with the front end's tests): six textured walls
// and two boxes, a 752x480 pair with 0.11 m baseline sliding 3 cm and turning 0.4 degrees per
// frame.
constexpr int kWidth = 752, kHeight = 480;
constexpr double kFocal = 460.0, kBaseline = 0.11;

Eigen::Isometry3d pose(int k) {
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, 0, 1, 0, -1, 0;  // columns: x, -z, y of the world
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  // Back and forth so long runs stay inside the room.
  const double s = 0.03 * (k % 40 < 20 ? k % 40 : 40 - k % 40);
  T.translation() = Eigen::Vector3d(-0.3 + s, -1.5, 1.3);
  T.linear() = Eigen::AngleAxisd(0.25 * s, Eigen::Vector3d::UnitZ()) * R;
  return T;
}

// CPU time of the whole process: with one OpenCV thread it is the front end's own work,
// whatever else loads the machine (wall times on a shared machine are not).
double processCpuMs() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return 1e3 * static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_nsec);
}

struct Series {
  std::vector<double> cpu;
  std::vector<double> total, pyramid, track, detect, stereo, features, stereo_matched;
  void add(const FrameFeatures& f) {
    total.push_back(f.stats.process_time_ms);
    pyramid.push_back(f.stats.pyramid_ms);
    track.push_back(f.stats.track_ms);
    detect.push_back(f.stats.detect_ms);
    stereo.push_back(f.stats.stereo_ms);
    features.push_back(static_cast<double>(f.features.size()));
    stereo_matched.push_back(f.stats.stereo_matched);
  }
};

Json summary(const std::string& name, const Series& s) {
  std::fprintf(stderr,
               "strata-bench frontend: %s median %.2f ms wall, %.2f ms CPU per stereo frame\n",
               name.c_str(), quantile(s.total, 0.5), quantile(s.cpu, 0.5));
  return Json::object()
      .set("sequence", name)
      .set("frames", static_cast<int>(s.total.size()))
      .set("cpu_ms_per_frame_median", quantile(s.cpu, 0.5))
      .set("cpu_ms_per_frame_p90", quantile(s.cpu, 0.9))
      .set("ms_per_frame_median", quantile(s.total, 0.5))
      .set("ms_per_frame_p90", quantile(s.total, 0.9))
      .set("ms_per_frame_max", quantile(s.total, 1.0))
      .set("ms_mean_pyramid", mean(s.pyramid))
      .set("ms_mean_track", mean(s.track))
      .set("ms_mean_detect", mean(s.detect))
      .set("ms_mean_stereo", mean(s.stereo))
      .set("features_mean", mean(s.features))
      .set("stereo_matched_mean", mean(s.stereo_matched));
}

Json benchSim(int frames) {
  const sim::AnalyticRayScene scene = sim::makeStereoTestRoom(0);
  sim::GreyCameraConfig config;
  config.intrinsics.width_px = kWidth;
  config.intrinsics.height_px = kHeight;
  config.intrinsics.fx_px = config.intrinsics.fy_px = static_cast<float>(kFocal);
  config.intrinsics.cx_px = 0.5f * (kWidth - 1);
  config.intrinsics.cy_px = 0.5f * (kHeight - 1);
  config.baseline_m = kBaseline;
  const sim::GreyCamera camera(config);
  odometry::StereoCamera rig;
  rig.left = odometry::Camera::fromIntrinsics(config.intrinsics, "sim left");
  rig.right = odometry::Camera::fromIntrinsics(config.intrinsics, "sim right");
  rig.right.T_B_C = Eigen::Isometry3d(Eigen::Translation3d(kBaseline, 0, 0));
  std::vector<cv::Mat> left, right;  // rendered before timing
  for (int k = 0; k <= frames; ++k) {
    const sim::GreyFrame f = camera.render(scene, pose(k), sim::Lighting{}, k);
    left.push_back(
        cv::Mat(kHeight, kWidth, CV_8UC1, const_cast<std::uint8_t*>(f.eyes[0].pixels.data()))
            .clone());
    right.push_back(
        cv::Mat(kHeight, kWidth, CV_8UC1, const_cast<std::uint8_t*>(f.eyes[1].pixels.data()))
            .clone());
  }
  odometry::FeatureTracker tracker(rig, odometry::FrontendConfig{});
  Series series;
  for (int k = 0; k <= frames; ++k) {
    const double cpu_start = processCpuMs();
    const FrameFeatures f = tracker.process(50'000'000LL * (k + 1), left[k], right[k]);
    if (k > 0) {
      series.cpu.push_back(processCpuMs() - cpu_start);
      series.add(f);
    }
    if (f.stats.lost)
      throw Error("front end lost track on the simulated sequence, frame " + std::to_string(k));
  }
  return summary("sim_room_752x480", series);
}

// EuRoC: NOTE a minimal local parse of sensor.yaml and data.csv (as test_frontend_tracking's),
// until the project's EuRoC reader lands.
std::vector<double> yamlList(const std::string& text, const std::string& key) {
  const std::size_t at = text.find(key + ":");
  if (at == std::string::npos) throw InputError("sensor.yaml: no key '" + key + "'");
  const std::size_t open = text.find('[', at), close = text.find(']', open);
  std::string list = text.substr(open + 1, close - open - 1);
  std::replace(list.begin(), list.end(), ',', ' ');
  std::istringstream in(list);
  std::vector<double> values;
  for (double v; in >> v;) values.push_back(v);
  return values;
}

odometry::Camera eurocCamera(const std::string& folder) {
  std::ifstream file(folder + "/sensor.yaml");
  std::stringstream text;
  text << file.rdbuf();
  const std::string yaml = text.str();
  const std::vector<double> size = yamlList(yaml, "resolution"), k = yamlList(yaml, "intrinsics");
  const std::vector<double> d = yamlList(yaml, "distortion_coefficients");
  const std::vector<double> T = yamlList(yaml.substr(yaml.find("T_BS")), "data");
  if (size.size() != 2 || k.size() != 4 || d.size() != 4 || T.size() != 16) {
    throw InputError(folder + "/sensor.yaml: unexpected list lengths");
  }
  odometry::Camera c;
  c.name = folder;
  c.width_px = static_cast<int>(size[0]);
  c.height_px = static_cast<int>(size[1]);
  c.fx_px = k[0], c.fy_px = k[1], c.cx_px = k[2], c.cy_px = k[3];
  c.distortion = odometry::DistortionModel::kRadialTangential;
  c.coefficients = {d[0], d[1], d[2], d[3]};
  c.T_B_C.matrix() = Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(T.data());
  return c;
}

std::map<std::int64_t, std::string> eurocImages(const std::string& folder) {
  std::ifstream csv(folder + "/data.csv");
  std::map<std::int64_t, std::string> images;
  for (std::string line; std::getline(csv, line);) {
    if (line.empty() || line[0] == '#') continue;
    const std::size_t comma = line.find(',');
    std::string name = line.substr(comma + 1);
    name.erase(std::remove_if(name.begin(), name.end(), ::isspace), name.end());
    images[std::stoll(line.substr(0, comma))] = folder + "/data/" + name;
  }
  return images;
}

Json benchEuroc(const std::string& mav0) {
  odometry::StereoCamera rig{eurocCamera(mav0 + "/cam0"), eurocCamera(mav0 + "/cam1")};
  const auto left = eurocImages(mav0 + "/cam0"), right = eurocImages(mav0 + "/cam1");
  std::vector<std::pair<std::int64_t, std::pair<cv::Mat, cv::Mat>>> frames;  // decoded first
  for (const auto& [t, path] : left) {
    const auto r = right.find(t);
    if (r == right.end()) continue;
    frames.push_back(
        {t, {cv::imread(path, cv::IMREAD_UNCHANGED), cv::imread(r->second, cv::IMREAD_UNCHANGED)}});
  }
  if (frames.size() < 2) throw InputError(mav0 + ": fewer than 2 stereo pairs");
  odometry::FeatureTracker tracker(rig, odometry::FrontendConfig{});
  Series series;
  for (std::size_t k = 0; k < frames.size(); ++k) {
    const double cpu_start = processCpuMs();
    const FrameFeatures f =
        tracker.process(frames[k].first, frames[k].second.first, frames[k].second.second);
    if (k > 0) {
      series.cpu.push_back(processCpuMs() - cpu_start);
      series.add(f);
    }
  }
  return summary("euroc_v101_micro", series);
}

}  // namespace

CLI::App* addFrontendCommand(CLI::App& app, FrontendBenchOptions& o) {
  CLI::App* c = app.add_subcommand("frontend", "Visual front end: ms per stereo frame");
  c->add_option("--frames", o.frames, "Simulated stereo frames timed")->capture_default_str();
  c->add_option("--threads", o.threads, "OpenCV threads")->capture_default_str();
  c->add_option("--euroc", o.euroc_mav0, "EuRoC mav0 folder (default: the shared excerpt)");
  c->add_option("--out", o.out_path, "Also write the JSON here");
  return c;
}

int runFrontendBench(const FrontendBenchOptions& o) {
  try {
    const std::string load_at_start = loadAverage();
    cv::setNumThreads(o.threads);
    Json results = Json::array();
    results.push(benchSim(o.frames));
    const std::string mav0 = o.euroc_mav0.empty()
                                 ? std::string(STRATA_SHARED_DATA_DIR) + "/euroc_v101_micro/mav0"
                                 : o.euroc_mav0;
    if (std::filesystem::is_directory(mav0)) {
      results.push(benchEuroc(mav0));
    } else {
      std::fprintf(stderr, "strata-bench frontend: no EuRoC excerpt at %s, skipped\n",
                   mav0.c_str());
    }
    Json report = Json::object()
                      .set("benchmark", "frontend")
                      .set("machine", machineInfo("host CPU (OpenCV KLT)", load_at_start))
                      .set("opencv_threads", o.threads)
                      .set("results", results);
    emitReport(report, o.out_path);
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench frontend: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench frontend: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

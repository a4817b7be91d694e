#include "cli/demo_localize.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <sstream>

#include "cli/demo_align.h"
#include "cli/report_json.h"
#include "strata/core/parallel_for.h"
#include "strata/core/progress.h"
#include "strata/core/statistics.h"
#include "strata/localize/session_localization.h"
#include "strata/sim/sensors/odometry_frame.h"

namespace strata::apps {
namespace {

constexpr double kWrong_m = 0.5;
constexpr double kWrong_deg = 10.0;

/// Session 0's frames as the prior map, at its given (odometry) poses.
localize::PriorMap teachMap(const sim::SimSessionDataset& teach, bool quiet) {
  const localize::PriorMapConfig config;
  std::vector<localize::MapKeyframe> keyframes(teach.size());
  ProgressBar bar("localize: the map of " + teach.name(), teach.size(), !quiet);
  std::atomic<std::size_t> done{0};
  std::mutex bar_mutex;
  parallelForEach(teach.size(), config.threads, [&](std::size_t i) {
    keyframes[i] = localize::describeKeyframe(teach.load(i), teach.intrinsics(), config);
    const std::size_t finished = ++done;
    std::lock_guard<std::mutex> lock(bar_mutex);
    bar.update(finished);
  });
  bar.finish();
  return localize::PriorMap(std::move(keyframes), config);
}

}  // namespace

DemoLocalizeResult useLocalizedPoses(
    const std::vector<std::shared_ptr<sim::SimSessionDataset>>& sessions, bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Eigen::Isometry3d> T_W_S;  // each session's true odometry frame
  for (const auto& session : sessions) {
    T_W_S.push_back(sim::randomOdometryFrame(sim::OdometryFrameConfig{}, session->seed()));
    session->replaceGivenPoses(mapped(T_W_S.back().inverse(), session->givenPoses()));
  }
  DemoLocalizeResult out;
  const localize::PriorMap map = teachMap(*sessions.front(), quiet);
  out.map_keyframes = map.keyframes().size();
  localize::SessionLocalizationConfig config;
  config.check_frames = 0;  // a repeat of the same world: nothing to refuse
  for (std::size_t s = 1; s < sessions.size(); ++s) {
    sim::SimSessionDataset& session = *sessions[s];
    ProgressBar bar("localize: " + session.name(), session.size(), !quiet);
    const localize::SessionLocalization result = localize::localizeSession(
        session, session.givenPoses(), map, config, [&](std::size_t done, std::size_t) {
          bar.update(done);
          return true;
        });
    bar.finish();
    DemoLocalizeSession r;
    r.name = session.name();
    r.frames = result.frames.size();
    r.attempted = result.attempted;
    r.localized = result.localized;
    r.rejected = result.rejected;
    std::vector<std::optional<Eigen::Isometry3d>> poses;
    std::vector<double> errors, times;
    const Eigen::Isometry3d odometry_to_truth =
        session.truePoses().front() * session.givenPoses().front().inverse();
    for (const localize::FrameLocalization& f : result.frames) {
      const Eigen::Isometry3d& truth = session.truePoses()[f.frame];
      r.odometry_max_error_m = std::max(
          r.odometry_max_error_m,
          ((odometry_to_truth * session.givenPoses()[f.frame]).translation() - truth.translation())
              .norm());
      if (f.attempted) times.push_back(f.localization.time_ms);
      if (!f.placed()) {
        poses.emplace_back(std::nullopt);
        continue;
      }
      ++r.placed;
      const Eigen::Isometry3d T_W_C = T_W_S[0] * f.fused.T_W_C;
      const Eigen::Isometry3d d = truth.inverse() * T_W_C;
      const double e = d.translation().norm();
      const double a = Eigen::AngleAxisd(d.linear()).angle() * 180.0 / M_PI;
      errors.push_back(e);
      r.wrong += (e > kWrong_m || a > kWrong_deg) ? 1 : 0;
      poses.emplace_back(T_W_C);
    }
    if (!errors.empty()) {
      r.median_error_m = median(errors);
      r.max_error_m = *std::max_element(errors.begin(), errors.end());
    }
    if (!times.empty()) r.median_localization_ms = median(times);
    session.replaceGivenPoses(poses);
    out.sessions.push_back(r);
  }
  sessions.front()->replaceGivenPoses(mapped(T_W_S[0], sessions.front()->givenPoses()));
  out.localize_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::string demoLocalizeJson(const DemoLocalizeResult& r) {
  Json j;
  j["map_keyframes"] = r.map_keyframes;
  j["localize_s"] = r.localize_s;
  Json sessions = Json::array();
  for (const DemoLocalizeSession& s : r.sessions) {
    Json e;
    e["name"] = s.name;
    e["frames"] = s.frames;
    e["attempted"] = s.attempted;
    e["localized"] = s.localized;
    e["placed"] = s.placed;
    e["rejected_by_fusion"] = s.rejected;
    e["wrong"] = s.wrong;
    e["median_error_m"] = s.median_error_m;
    e["max_error_m"] = s.max_error_m;
    e["odometry_max_error_m"] = s.odometry_max_error_m;
    e["median_localization_ms"] = s.median_localization_ms;
    sessions.push_back(e);
  }
  j["sessions"] = sessions;
  return jsonText(j);
}

std::string summarizeDemoLocalize(const DemoLocalizeResult& r) {
  std::size_t attempted = 0, localized = 0, placed = 0, frames = 0, wrong = 0;
  double worst = 0.0, odometry = 0.0;
  for (const DemoLocalizeSession& s : r.sessions) {
    attempted += s.attempted;
    localized += s.localized;
    placed += s.placed;
    frames += s.frames;
    wrong += s.wrong;
    worst = std::max(worst, s.max_error_m);
    odometry = std::max(odometry, s.odometry_max_error_m);
  }
  std::ostringstream o;
  o.precision(3);
  o << "Repeats localised against the teach session's map (" << r.map_keyframes
    << " keyframes): " << localized << " of " << attempted << " frames localised, " << placed
    << " of " << frames << " placed, " << wrong << " wrong; largest error " << 1e3 * worst
    << " mm (odometry alone: " << 1e3 * odometry << " mm), " << r.localize_s << " s.";
  return o.str();
}

}  // namespace strata::apps

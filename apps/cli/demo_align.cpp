#include "cli/demo_align.h"

#include <chrono>
#include <map>
#include <sstream>

#include "cli/report_json.h"
#include "strata/sim/sensors/odometry_frame.h"

namespace strata::apps {

std::vector<std::optional<Eigen::Isometry3d>> mapped(const Eigen::Isometry3d& T,
                                                     const std::vector<Eigen::Isometry3d>& poses) {
  std::vector<std::optional<Eigen::Isometry3d>> out;
  for (const Eigen::Isometry3d& p : poses) out.emplace_back(T * p);
  return out;
}

DemoAlignResult useAlignedPoses(const std::vector<std::shared_ptr<sim::SimSessionDataset>>& sessions,
                                bool quiet) {
  const auto start = std::chrono::steady_clock::now();
  std::vector<Eigen::Isometry3d> T_W_S;  // each session's true odometry frame
  for (const auto& session : sessions) {
    T_W_S.push_back(sim::randomOdometryFrame(sim::OdometryFrameConfig{}, session->seed()));
    session->replaceGivenPoses(mapped(T_W_S.back().inverse(), session->givenPoses()));
  }
  std::vector<align::AlignSession> inputs;
  std::vector<align::SessionTruth> truth;
  for (const auto& session : sessions) {
    inputs.push_back(align::sessionFromDataset(*session));
    truth.emplace_back(session->truePoses().begin(), session->truePoses().end());
  }
  std::map<std::string, std::optional<ProgressBar>> bars;
  const auto progress = [&](const std::string& stage, std::size_t done, std::size_t total) {
    auto& bar = bars[stage];
    if (!bar) bar.emplace("align: " + stage, total, !quiet);
    bar->update(done);
    if (done == total) bar->finish();
  };
  const align::AlignConfig config;
  const align::AlignResult result = align::alignSessions(inputs, config, progress);
  DemoAlignResult out;
  out.score = align::scoreAlignment(result, truth, config);
  out.sessions = sessions.size();
  out.loops_verified = result.loops.size();
  for (const align::AlignLoop& loop : result.loops) out.loops_accepted += loop.accepted ? 1 : 0;
  for (std::size_t s = 0; s < sessions.size(); ++s) {
    const align::AlignedSession& aligned = result.sessions[s];
    out.aligned += aligned.aligned ? 1 : 0;
    // The common frame is session 0's odometry frame; T_W_S[0] takes it into the truth's world.
    sessions[s]->replaceGivenPoses(
        mapped(T_W_S[0], aligned.aligned ? aligned.frame_T_W_C : aligned.frame_T_S_C));
  }
  out.align_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::string demoAlignJson(const DemoAlignResult& r) {
  Json j;
  j["sessions"] = r.sessions;
  j["aligned"] = r.aligned;
  j["loops_verified"] = r.loops_verified;
  j["loops_accepted"] = r.loops_accepted;
  j["align_s"] = r.align_s;
  j["truth"] = parseJson(align::alignmentScoreJson(r.score));
  return jsonText(j);
}

std::string summarizeDemoAlign(const DemoAlignResult& r) {
  std::ostringstream o;
  o.precision(3);
  o << "Alignment from images and depth alone: " << r.aligned << " of " << r.sessions
    << " sessions registered in " << r.align_s << " s, " << r.loops_accepted << " loops kept of "
    << r.loops_verified << " verified (" << r.score.accepted_false
    << " false by the truth); ATE " << 1e3 * r.score.ate_after_rmse_m
    << " mm in the common frame (odometry in its own frames: " << r.score.ate_before_rmse_m
    << " m).";
  return o.str();
}

}  // namespace strata::apps

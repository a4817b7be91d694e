#include "align_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <memory>

#include "strata/align/alignment_eval.h"
#include "strata/align/session_alignment.h"
#include "strata/core/dataset.h"
#include "strata/core/error.h"
#include "json.h"
#include "machine_info.h"
#include "strata/sim/sensors/odometry_frame.h"
#include "strata/sim/session/sim_session.h"
#include "strata/sim/world/world_paths.h"

namespace strata::bench {
namespace {

using Session = std::unique_ptr<sim::SimSessionDataset>;

/// Frames rendered once and held in memory, so that the timed stages do not include rendering.
class RenderedFrames : public Dataset {
 public:
  explicit RenderedFrames(const sim::SimSessionDataset& session)
      : name_(session.name()), intrinsics_(session.intrinsics()) {
    for (std::size_t i = 0; i < session.size(); ++i) frames_.push_back(session.load(i));
  }
  std::string name() const override { return name_; }
  std::size_t size() const override { return frames_.size(); }
  CameraIntrinsics intrinsics() const override { return intrinsics_; }
  RgbdFrame load(std::size_t index) const override { return frames_.at(index); }

 private:
  std::string name_;
  CameraIntrinsics intrinsics_;
  std::vector<RgbdFrame> frames_;
};

/// A session whose given poses are its drifted odometry in a random frame of its own.
Session makeSession(const std::shared_ptr<const sim::World>& world, int index,
                    const AlignBenchOptions& o) {
  sim::SimSessionConfig config;
  config.max_frames = o.frames;
  config.drift = true;
  if (!o.flat_color) config.camera.color_texture = sim::WorldTextureConfig{};
  auto session = std::make_unique<sim::SimSessionDataset>(world, index, config);
  const Eigen::Isometry3d T_S_W =
      sim::randomOdometryFrame(sim::OdometryFrameConfig{}, session->seed()).inverse();
  std::vector<std::optional<Eigen::Isometry3d>> own;
  for (const Eigen::Isometry3d& T_W_C : session->givenPoses()) own.emplace_back(T_S_W * T_W_C);
  session->replaceGivenPoses(own);
  return session;
}

double perKeyframeMs(double seconds, std::size_t keyframes) {
  return keyframes > 0 ? 1e3 * seconds / static_cast<double>(keyframes) : 0.0;
}

}  // namespace

CLI::App* addAlignCommand(CLI::App& app, AlignBenchOptions& o) {
  CLI::App* c = app.add_subcommand(
      "align", "Multi-session alignment on simulated sessions: ms per keyframe per stage");
  c->add_option("--world", o.world, "Shipped world")->capture_default_str();
  c->add_option("--sessions", o.sessions, "Sessions")->capture_default_str();
  c->add_option("--frames", o.frames, "Frames (keyframes) per session")->capture_default_str();
  c->add_flag("--flat-color", o.flat_color, "Flat-shaded RGB (no surface texture)");
  c->add_option("--threads", o.threads, "Worker threads")->capture_default_str();
  c->add_option("--out", o.out_path, "Also write the JSON here");
  return c;
}

int runAlignBench(const AlignBenchOptions& o) {
  try {
    if (o.sessions < 2 || o.frames < 10 || o.threads < 1) {
      throw InputError("--sessions >= 2, --frames >= 10 and --threads >= 1 are needed");
    }
    const std::string load_at_start = loadAverage();
    const auto world =
        std::make_shared<const sim::World>(sim::World::load(sim::findWorld(o.world)));
    std::vector<Session> sessions;
    std::vector<std::unique_ptr<RenderedFrames>> rendered;
    std::vector<align::AlignSession> inputs;
    std::vector<align::SessionTruth> truth;
    // Rendering the keyframes is the simulator's cost, not the alignment's: done first.
    const auto render_start = std::chrono::steady_clock::now();
    for (int s = 0; s < o.sessions; ++s) {
      sessions.push_back(makeSession(world, s % world->sessionCount(), o));
      rendered.push_back(std::make_unique<RenderedFrames>(*sessions.back()));
      inputs.push_back(align::sessionFromDataset(*sessions.back(), &*rendered.back()));
      truth.emplace_back(sessions.back()->truePoses().begin(), sessions.back()->truePoses().end());
    }
    const double render_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - render_start).count();
    align::AlignConfig config;
    config.threads = config.graph.threads = o.threads;
    const align::AlignResult r = align::alignSessions(inputs, config);
    const align::AlignmentScore score = align::scoreAlignment(r, truth, config);
    const std::size_t k = r.times.keyframes;
    Json report =
        Json::object()
            .set("benchmark", "align")
            .set("machine", machineInfo("host CPU (OpenCV, hnswlib, Ceres)", load_at_start))
            .set("settings", Json::object()
                                 .set("world", o.world)
                                 .set("sessions", o.sessions)
                                 .set("keyframes_per_session", o.frames)
                                 .set("color", o.flat_color ? "flat" : "textured")
                                 .set("threads", o.threads))
            .set("results",
                 Json::object()
                     .set("keyframes", static_cast<int>(k))
                     .set("render_s_not_counted", render_s)
                     .set("features_ms_per_keyframe", perKeyframeMs(r.times.features_s, k))
                     .set("retrieval_ms_per_keyframe", perKeyframeMs(r.times.retrieval_s, k))
                     .set("verification_ms_per_keyframe",
                          perKeyframeMs(r.times.verification_s, k))
                     .set("loop_detection_ms_per_keyframe",
                          perKeyframeMs(r.times.retrieval_s + r.times.verification_s, k))
                     .set("candidates_verified", static_cast<int>(r.candidates))
                     .set("verification_ms_per_candidate",
                          perKeyframeMs(r.times.verification_s, r.candidates))
                     .set("graph_s", r.times.graph_s)
                     .set("sessions_aligned", static_cast<int>(score.aligned_sessions))
                     .set("loops_kept_true", static_cast<int>(score.accepted_true))
                     .set("loops_kept_false", static_cast<int>(score.accepted_false))
                     .set("ate_before_m", score.ate_before_rmse_m)
                     .set("ate_after_m", score.ate_after_rmse_m));
    emitReport(report, o.out_path);
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench align: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench align: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench

// Alignment of a map database's sessions: inputs from the store and the session folders, results
// back into the store.
#include "strata/align/store_alignment.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>

#include "strata/core/error.h"
#include "strata/core/pose_interpolation.h"
#include "strata/io/tum_format.h"
#include "strata/io/open_dataset.h"

namespace strata::align {
namespace {

namespace fs = std::filesystem;
constexpr double kMaxStampDifference_s = 0.02;  // the import's association window

std::string sessionWhat(const store::SessionRecord& s) {
  return "session " + std::to_string(s.id) + " '" + s.name + "' (" + s.source_folder + ")";
}

/// Information of each odometry edge between consecutive keyframes (the import's, or a later
/// stage's); the pose graph's default where a pair has none.
std::vector<store::Matrix6d> odometryInformation(const std::vector<std::int64_t>& ids,
                                                 const std::vector<store::EdgeRecord>& edges,
                                                 const store::Matrix6d& fallback) {
  std::map<std::pair<std::int64_t, std::int64_t>, store::Matrix6d> by_pair;
  for (const store::EdgeRecord& e : edges)
    if (e.to_keyframe) by_pair[{e.from_keyframe, *e.to_keyframe}] = e.information;
  std::vector<store::Matrix6d> out;
  for (std::size_t k = 0; k + 1 < ids.size(); ++k) {
    const auto found = by_pair.find({ids[k], ids[k + 1]});
    out.push_back(found != by_pair.end() ? found->second : fallback);
  }
  return out;
}

void loadSession(store::Store& store, const store::SessionRecord& record,
                 const std::vector<store::EdgeRecord>& odometry_edges, const AlignConfig& config,
                 StoreAlignment& out, AlignSession& session) {
  out.odometry_files.push_back(sessionOdometryFile(record.source_folder));
  out.datasets.push_back(openStoredSession(store, record));
  const Dataset& frames = *out.datasets.back();
  session.name = record.name;
  session.frames = &frames;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const FrameStamp stamp = frames.stamp(i);
    session.frame_timestamps_s.push_back(stamp.timestamp_s);
    session.frame_T_S_C.push_back(stamp.T_W_C);  // the trajectory file is the odometry
  }
  std::vector<std::int64_t> ids;
  for (const store::KeyframeRecord& k : store.keyframes(record.id)) {
    const std::size_t frame = keyframeFrame(session.frame_timestamps_s, k.timestamp_s, record);
    if (!session.keyframes.empty() && frame <= session.keyframes.back()) continue;  // same frame
    session.keyframes.push_back(frame);
    ids.push_back(k.id);
    session.stored_features.push_back(store.features(k.id));
  }
  session.odometry_information =
      odometryInformation(ids, odometry_edges, config.graph.default_odometry_information);
  out.keyframe_ids.push_back(std::move(ids));
}

void writeResults(store::Store& store, const StoreAlignment& a) {
  store::Transaction transaction = store.beginTransaction();
  store.clearAlignment();
  for (std::size_t s = 0; s < a.sessions.size(); ++s) {
    const AlignedSession& session = a.result.sessions[s];
    const std::vector<std::int64_t>& ids = a.keyframe_ids[s];
    for (std::size_t k = 0; k < ids.size(); ++k)
      store.setFeatures(ids[k], toFeatureSet(session.features[k]));
    if (!session.aligned) continue;
    std::vector<std::pair<std::int64_t, Eigen::Isometry3d>> poses;
    for (std::size_t k = 0; k < ids.size(); ++k) poses.emplace_back(ids[k], session.keyframe_T_W_C[k]);
    store.setOptimisedPoses(poses);
    store.setSessionAlignment(a.sessions[s].id, *session.T_W_S);
  }
  std::vector<store::EdgeRecord> loops;
  for (const AlignLoop& loop : a.result.loops) {
    store::EdgeRecord e;
    e.kind = store::EdgeKind::kLoop;
    e.from_keyframe = a.keyframe_ids[loop.session_a][loop.keyframe_a];
    e.to_keyframe = a.keyframe_ids[loop.session_b][loop.keyframe_b];
    e.T_from_to = loop.measurement.T_a_b;
    e.information = loop.measurement.information;
    e.loop = store::LoopStats{loop.measurement.inliers, loop.measurement.inlier_ratio,
                              loop.measurement.residual_m, loop.accepted};
    loops.push_back(e);
  }
  store.addEdges(loops);
  transaction.commit();
}

}  // namespace

std::unique_ptr<Dataset> openStoredSession(store::Store& store, const store::SessionRecord& record) {
  const std::string what = sessionWhat(record);
  if (!fs::is_directory(record.source_folder)) throw InputError(what + ": the folder is gone");
  const std::vector<store::ResourceProblem> problems = store.verifyResources(record.id);
  if (!problems.empty()) {
    throw InputError(what + ": " + std::to_string(problems.size()) +
                     " file(s) changed since the import, first: " + problems.front().message);
  }
  DatasetOptions options;
  options.trajectory_file = sessionOdometryFile(record.source_folder);
  return openDataset(record.source_folder, options);
}

std::size_t keyframeFrame(const std::vector<double>& times_s, double timestamp_s,
                          const store::SessionRecord& record) {
  const auto after = std::lower_bound(times_s.begin(), times_s.end(), timestamp_s);
  std::size_t best = times_s.size();
  double best_dt = kMaxStampDifference_s;
  for (auto it : {after, after == times_s.begin() ? after : after - 1}) {
    if (it == times_s.end()) continue;
    const double dt = std::abs(*it - timestamp_s);
    if (dt <= best_dt) best = static_cast<std::size_t>(it - times_s.begin()), best_dt = dt;
  }
  if (best == times_s.size()) {
    throw InputError(sessionWhat(record) + ": keyframe at " + std::to_string(timestamp_s) +
                     " s has no frame within 20 ms in the folder (it changed since the import?)");
  }
  return best;
}

std::string sessionOdometryFile(const std::string& folder) {
  const fs::path dir = fs::absolute(folder);
  const fs::path odometry = dir / "odometry.txt";
  return (fs::exists(odometry) ? odometry : dir / "groundtruth.txt").string();
}

StoreAlignment alignStore(store::Store& store, const AlignConfig& config,
                          const AlignProgress& progress) {
  config.validate();
  StoreAlignment out;
  out.sessions = store.sessions();
  if (out.sessions.empty()) throw InputError("map database '" + store.path() + "' has no session");
  const std::vector<store::EdgeRecord> odometry_edges = store.edges(store::EdgeKind::kOdometry);
  std::vector<AlignSession> sessions(out.sessions.size());
  for (std::size_t s = 0; s < out.sessions.size(); ++s)
    loadSession(store, out.sessions[s], odometry_edges, config, out, sessions[s]);
  out.result = alignSessions(sessions, config, progress);
  writeResults(store, out);
  return out;
}

std::optional<std::vector<SessionTruth>> loadStoreTruth(const StoreAlignment& a) {
  std::vector<SessionTruth> truth;
  for (std::size_t s = 0; s < a.sessions.size(); ++s) {
    const fs::path file = fs::path(a.sessions[s].source_folder) / "groundtruth.txt";
    if (!fs::exists(file) || fs::equivalent(file, a.odometry_files[s])) return std::nullopt;
    const std::vector<tum::TimedPose> poses = tum::readTrajectory(file.string());
    SessionTruth session;
    for (double t : a.result.sessions[s].frame_timestamps_s) {
      session.push_back(interpolateStamped(
          poses, t, 0.1, [](const tum::TimedPose& p) { return p.timestamp_s; },
          [](const tum::TimedPose& p) { return p.T_W_C; }));
    }
    truth.push_back(std::move(session));
  }
  return truth;
}

}  // namespace strata::align

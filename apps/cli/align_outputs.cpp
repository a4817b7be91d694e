// The files of `strata align`.
#include "cli/align_outputs.h"

#include <cctype>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

#include "core/atomic_file.h"
#include "core/json_text.h"
#include "core/pose_interpolation.h"
#include "io/tum_format.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

std::string poseJson(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  const Eigen::Vector3d t = T.translation();
  std::ostringstream o;
  o << "{\"t_m\": [" << jsonNumber(t.x()) << ", " << jsonNumber(t.y()) << ", "
    << jsonNumber(t.z()) << "], \"q_xyzw\": [" << jsonNumber(q.x()) << ", " << jsonNumber(q.y())
    << ", " << jsonNumber(q.z()) << ", " << jsonNumber(q.w()) << "]}";
  return o.str();
}

std::string sessionsJson(const align::StoreAlignment& a) {
  std::ostringstream o;
  o << "[";
  for (std::size_t s = 0; s < a.sessions.size(); ++s) {
    const align::AlignedSession& r = a.result.sessions[s];
    std::size_t loops = 0;
    for (const align::AlignLoop& l : a.result.loops)
      if (l.accepted && (l.session_a == s || l.session_b == s)) ++loops;
    o << (s ? ", " : "") << "{\"index\": " << s << ", \"id\": " << a.sessions[s].id
      << ", \"name\": " << jsonQuoted(a.sessions[s].name)
      << ", \"folder\": " << jsonQuoted(a.sessions[s].source_folder)
      << ", \"odometry_file\": " << jsonQuoted(a.odometry_files[s])
      << ", \"frames\": " << r.frame_T_S_C.size() << ", \"keyframes\": " << r.keyframes.size()
      << ", \"aligned\": " << (r.aligned ? "true" : "false") << ", \"accepted_loops\": " << loops
      << ", \"T_W_S\": " << (r.T_W_S ? poseJson(*r.T_W_S) : "null") << "}";
  }
  o << "]";
  return o.str();
}

std::string reasonsJson(const std::vector<std::string>& reasons) {
  // Grouped by the reason's words: the figures in a reason ("12 below 25") vary per candidate.
  std::map<std::string, std::size_t> counts;
  for (const std::string& r : reasons) {
    std::string key;
    for (std::size_t i = 0; i < r.size(); ++i) {
      const bool number = std::isdigit(static_cast<unsigned char>(r[i])) ||
                          (r[i] == '.' && i + 1 < r.size() &&
                           std::isdigit(static_cast<unsigned char>(r[i + 1])));
      if (!number) key += r[i];
      else if (key.empty() || key.back() != '#') key += '#';
    }
    ++counts[key.empty() ? "unspecified" : key];
  }
  std::ostringstream o;
  o << "{";
  bool first = true;
  for (const auto& [reason, count] : counts) {
    o << (first ? "" : ", ") << jsonQuoted(reason) << ": " << count;
    first = false;
  }
  o << "}";
  return o.str();
}

}  // namespace

std::vector<std::string> writeAlignedTrajectories(const align::StoreAlignment& a,
                                                  const std::string& out_dir) {
  std::vector<std::string> files;
  for (std::size_t s = 0; s < a.result.sessions.size(); ++s) {
    const align::AlignedSession& r = a.result.sessions[s];
    if (!r.aligned) continue;
    const fs::path dir = fs::path(out_dir) / ("session_" + std::to_string(s));
    fs::create_directories(dir);
    std::ostringstream o;
    o << "# session " << s << " '" << a.sessions[s].name
      << "' aligned: timestamp tx ty tz qx qy qz qw (camera-to-world, common frame)\n";
    o << std::fixed << std::setprecision(6);
    for (std::size_t i = 0; i < r.frame_T_W_C.size(); ++i)
      o << r.frame_timestamps_s[i] << " " << tum::poseToTum(r.frame_T_W_C[i]) << "\n";
    files.push_back((dir / "trajectory.txt").string());
    writeTextAtomically(files.back(), o.str());
  }
  return files;
}

void writeLoopsCsv(const align::StoreAlignment& a, const align::AlignmentScore* score,
                   const std::string& path) {
  std::ostringstream o;
  o << "session_a,keyframe_a,timestamp_a_s,session_b,keyframe_b,timestamp_b_s,place_score,"
       "matches,inliers,inlier_ratio,residual_m,overlap,switch,accepted";
  if (score) o << ",true_loop,error_m,error_deg";
  o << "\n" << std::setprecision(6);
  for (std::size_t l = 0; l < a.result.loops.size(); ++l) {
    const align::AlignLoop& loop = a.result.loops[l];
    const align::LoopMeasurement& m = loop.measurement;
    o << loop.session_a << "," << loop.keyframe_a << ","
      << a.result.sessions[loop.session_a].keyframe_timestamps_s[loop.keyframe_a] << ","
      << loop.session_b << "," << loop.keyframe_b << ","
      << a.result.sessions[loop.session_b].keyframe_timestamps_s[loop.keyframe_b] << ","
      << loop.place_score << "," << m.matches << "," << m.inliers << "," << m.inlier_ratio << ","
      << m.residual_m << "," << m.overlap << "," << loop.switch_value << ","
      << (loop.accepted ? 1 : 0);
    if (score) {
      const align::LoopScore& ls = score->loops[l];
      o << "," << (ls.is_true ? 1 : 0) << "," << ls.translation_error_m << ","
        << ls.rotation_error_deg;
    }
    o << "\n";
  }
  writeTextAtomically(path, o.str());
}

void writeAlignReport(const align::StoreAlignment& a, const align::AlignmentScore* score,
                      const std::string& db_path, double total_s, const std::string& path) {
  const align::AlignResult& r = a.result;
  std::size_t accepted = 0, aligned = 0;
  for (const align::AlignLoop& l : r.loops) accepted += l.accepted ? 1 : 0;
  for (const align::AlignedSession& s : r.sessions) aligned += s.aligned ? 1 : 0;
  const double keyframes = std::max<double>(1.0, r.times.keyframes);
  std::ostringstream o;
  o << "{\n  \"database\": " << jsonQuoted(db_path) << ",\n  \"sessions\": " << sessionsJson(a)
    << ",\n  \"aligned_sessions\": " << aligned << ",\n  \"unaligned_sessions\": "
    << r.sessions.size() - aligned << ",\n  \"loops\": {\"candidates_verified\": " << r.candidates
    << ", \"verified\": " << r.loops.size() << ", \"accepted\": " << accepted
    << ", \"switched_off\": " << r.loops.size() - accepted
    << ", \"rejections\": " << reasonsJson(r.rejection_reasons) << "},\n  \"times\": {"
    << "\"keyframes\": " << r.times.keyframes << ", \"features_s\": " << jsonNumber(r.times.features_s)
    << ", \"retrieval_s\": " << jsonNumber(r.times.retrieval_s)
    << ", \"verification_s\": " << jsonNumber(r.times.verification_s)
    << ", \"graph_s\": " << jsonNumber(r.times.graph_s)
    << ", \"loop_detection_ms_per_keyframe\": "
    << jsonNumber(1e3 * (r.times.retrieval_s + r.times.verification_s) / keyframes)
    << ", \"total_s\": " << jsonNumber(total_s) << "},\n  \"pose_graph\": {\"iterations\": "
    << r.graph.iterations << ", \"initial_cost\": " << jsonNumber(r.graph.initial_cost)
    << ", \"final_cost\": " << jsonNumber(r.graph.final_cost)
    << ", \"solve_s\": " << jsonNumber(r.graph.solve_seconds) << "},\n  \"truth\": "
    << (score ? align::alignmentScoreJson(*score) : "null") << "\n}\n";
  writeTextAtomically(path, o.str());
}

std::optional<std::vector<align::SessionTruth>> loadAlignTruth(const align::StoreAlignment& a) {
  std::vector<align::SessionTruth> truth;
  for (std::size_t s = 0; s < a.sessions.size(); ++s) {
    const fs::path file = fs::path(a.sessions[s].source_folder) / "groundtruth.txt";
    if (!fs::exists(file) || fs::equivalent(file, a.odometry_files[s])) return std::nullopt;
    const std::vector<tum::TimedPose> poses = tum::readTrajectory(file.string());
    align::SessionTruth session;
    for (double t : a.result.sessions[s].frame_timestamps_s) {
      session.push_back(interpolateStamped(
          poses, t, 0.1, [](const tum::TimedPose& p) { return p.timestamp_s; },
          [](const tum::TimedPose& p) { return p.T_W_C; }));
    }
    truth.push_back(std::move(session));
  }
  return truth;
}

}  // namespace strata::apps

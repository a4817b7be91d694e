// The files of `strata align`.
#include "cli/align_outputs.h"

#include <cctype>
#include <filesystem>
#include <iomanip>
#include <map>
#include <sstream>

#include "cli/report_json.h"
#include "strata/core/atomic_file.h"
#include "strata/core/pose_interpolation.h"
#include "strata/io/tum_format.h"
#include "strata/io/tum_writer.h"

namespace strata::apps {
namespace {

namespace fs = std::filesystem;

Json poseJson(const Eigen::Isometry3d& T) {
  const Eigen::Quaterniond q(T.linear());
  Json j;
  j["t_m"] = jsonVector(Eigen::Vector3d(T.translation()));
  j["q_xyzw"] = Json::array({q.x(), q.y(), q.z(), q.w()});
  return j;
}

Json sessionsJson(const align::StoreAlignment& a) {
  Json sessions = Json::array();
  for (std::size_t s = 0; s < a.sessions.size(); ++s) {
    const align::AlignedSession& r = a.result.sessions[s];
    std::size_t loops = 0;
    for (const align::AlignLoop& l : a.result.loops)
      if (l.accepted && (l.session_a == s || l.session_b == s)) ++loops;
    Json j;
    j["index"] = s;
    j["id"] = a.sessions[s].id;
    j["name"] = a.sessions[s].name;
    j["folder"] = a.sessions[s].source_folder;
    j["odometry_file"] = a.odometry_files[s];
    j["frames"] = r.frame_T_S_C.size();
    j["keyframes"] = r.keyframes.size();
    j["aligned"] = r.aligned;
    j["accepted_loops"] = loops;
    j["T_W_S"] = r.T_W_S ? poseJson(*r.T_W_S) : Json(nullptr);
    sessions.push_back(std::move(j));
  }
  return sessions;
}

Json reasonsJson(const std::vector<std::string>& reasons) {
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
  Json j = Json::object();
  for (const auto& [reason, count] : counts) j[reason] = count;
  return j;
}

Json loopsJson(const align::AlignResult& r) {
  std::size_t accepted = 0;
  for (const align::AlignLoop& l : r.loops) accepted += l.accepted ? 1 : 0;
  Json j;
  j["candidates_verified"] = r.candidates;
  j["verified"] = r.loops.size();
  j["accepted"] = accepted;
  j["switched_off"] = r.loops.size() - accepted;
  j["rejections"] = reasonsJson(r.rejection_reasons);
  return j;
}

Json timesJson(const align::AlignResult& r, double total_s) {
  const double keyframes = std::max<double>(1.0, r.times.keyframes);
  Json j;
  j["keyframes"] = r.times.keyframes;
  j["features_s"] = r.times.features_s;
  j["retrieval_s"] = r.times.retrieval_s;
  j["verification_s"] = r.times.verification_s;
  j["graph_s"] = r.times.graph_s;
  j["loop_detection_ms_per_keyframe"] =
      1e3 * (r.times.retrieval_s + r.times.verification_s) / keyframes;
  j["total_s"] = total_s;
  return j;
}

Json poseGraphJson(const align::AlignResult& r) {
  Json j;
  j["iterations"] = r.graph.iterations;
  j["initial_cost"] = r.graph.initial_cost;
  j["final_cost"] = r.graph.final_cost;
  j["solve_s"] = r.graph.solve_seconds;
  return j;
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
    std::vector<tum::TimedPose> poses;
    for (std::size_t i = 0; i < r.frame_T_W_C.size(); ++i)
      poses.push_back({r.frame_timestamps_s[i], r.frame_T_W_C[i]});
    files.push_back((dir / "trajectory.txt").string());
    writeTumTrajectory(files.back(), poses,
                       {"session " + std::to_string(s) + " '" + a.sessions[s].name +
                        "' aligned: timestamp tx ty tz qx qy qz qw (camera-to-world, common frame)"});
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
  std::size_t aligned = 0;
  for (const align::AlignedSession& s : r.sessions) aligned += s.aligned ? 1 : 0;
  Json j;
  j["database"] = db_path;
  j["sessions"] = sessionsJson(a);
  j["aligned_sessions"] = aligned;
  j["unaligned_sessions"] = r.sessions.size() - aligned;
  j["loops"] = loopsJson(r);
  j["times"] = timesJson(r, total_s);
  j["pose_graph"] = poseGraphJson(r);
  j["truth"] = score ? parseJson(align::alignmentScoreJson(*score)) : Json(nullptr);
  writeTextAtomically(path, jsonFileText(j));
}

}  // namespace strata::apps

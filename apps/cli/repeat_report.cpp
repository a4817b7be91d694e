#include "cli/repeat_report.h"

#include <cstdio>
#include <map>

#include "strata/core/atomic_file.h"

namespace strata::apps {

Json repeatRunJson(const std::string& mode, const repeat::RepeatResult& r) {
  Json j;
  j["mode"] = mode;
  j["finished"] = r.finished;
  j["stop_reason"] = r.stop_reason;
  j["following_error_m"] = {{"rms", r.following_rms_m},
                            {"max", r.following_max_m},
                            {"measured", "true position vs the teach's true path"}};
  j["path_length_m"] = r.path_length_m;
  j["taught_length_m"] = r.taught_length_m;
  j["progress_m"] = r.progress_m;
  j["drift_m"] = {{"final", r.drift_final_m},
                  {"max", r.drift_max_m},
                  {"odometry_final", r.odometry_drift_final_m},
                  {"measured", "|estimate - truth| of the camera centre"}};
  const std::size_t attempts = r.localizations.size();
  j["localization"] = {
      {"enabled", r.localization},
      {"attempts", attempts},
      {"localized", r.localized},
      {"localized_fraction", attempts > 0 ? double(r.localized) / double(attempts) : 0.0},
      {"accepted", r.accepted},
      {"rejected", r.rejected},
      {"time_ms", {{"mean", r.localize_ms_mean}, {"max", r.localize_ms_max}}}};
  std::map<std::string, std::size_t> reasons;
  for (const repeat::LocalizationRecord& l : r.localizations) {
    if (!l.accepted) ++reasons[l.note.empty() ? "(no reason given)" : l.note];
  }
  Json why = Json::object();
  for (const auto& [reason, count] : reasons) why[reason] = count;
  j["localization"]["not_accepted_reasons"] = why;
  Json stops = Json::array();
  for (const repeat::RepeatStop& s : r.stops) {
    stops.push_back({{"t_s", s.t_s},
                     {"position", jsonVector(s.p_W)},
                     {"reason", s.reason},
                     {"resumed", s.resumed}});
  }
  j["stops"] = stops;
  j["detours"] = r.detours;
  Json events = Json::array();
  for (const repeat::Collision& c : r.collisions) {
    events.push_back({{"t_s", c.t_s},
                      {"position", jsonVector(c.p_W)},
                      {"clearance_m", jsonFloat(c.clearance_m)}});
  }
  j["collisions"] = {{"count", r.collisions.size()},
                     {"min_clearance_m", jsonFloat(r.min_clearance_m)},
                     {"events", events}};
  j["sim_time_s"] = r.sim_time_s;
  j["wall_s"] = r.wall_s;
  return j;
}

void writeRepeatCsv(const std::string& path, const repeat::RepeatResult& r) {
  std::string text = "t_s,true_x,true_y,true_z,est_x,est_y,est_z,following_error_m\n";
  char line[256];
  for (std::size_t i = 0; i < r.t_s.size(); ++i) {
    const Eigen::Vector3f& p = r.true_W[i];
    const Eigen::Vector3f& e = r.estimate_M[i];
    std::snprintf(line, sizeof(line), "%.2f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f\n", r.t_s[i], p.x(),
                  p.y(), p.z(), e.x(), e.y(), e.z(),
                  i < r.following_error_m.size() ? r.following_error_m[i] : 0.0f);
    text += line;
  }
  writeTextAtomically(path, text);
}

}  // namespace strata::apps

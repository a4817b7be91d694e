#include "cli/map_info.h"

#include <cstdarg>
#include <cstdio>

#include "cli/report_json.h"
#include "strata/store/schema.h"

namespace strata::apps {

namespace {

std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
std::string format(const char* fmt, ...) {
  char text[512];
  va_list args;
  va_start(args, fmt);
  std::vsnprintf(text, sizeof(text), fmt, args);
  va_end(args);
  return text;
}

const char* problemName(store::ResourceProblem::Kind kind) {
  switch (kind) {
    case store::ResourceProblem::Kind::kMissing:
      return "missing";
    case store::ResourceProblem::Kind::kSizeChanged:
      return "size_changed";
    case store::ResourceProblem::Kind::kChecksumChanged:
      return "checksum_changed";
  }
  return "?";
}

Json sessionSummaryJson(const store::SessionSummary& s) {
  Json j;
  j["id"] = s.session.id;
  j["name"] = s.session.name;
  j["source_folder"] = s.session.source_folder;
  j["aligned"] = s.session.aligned;
  j["keyframes"] = s.keyframes;
  j["optimised_keyframes"] = s.optimised_keyframes;
  j["odometry_edges"] = s.odometry_edges;
  j["loop_edges"] = s.loop_edges;
  j["prior_edges"] = s.prior_edges;
  j["resources"] = s.resources;
  j["resource_bytes"] = s.resource_bytes;
  j["path_length_m"] = s.path_length_m;
  j["first_timestamp_s"] = s.first_timestamp_s;
  j["last_timestamp_s"] = s.last_timestamp_s;
  return j;
}

Json problemJson(const store::ResourceProblem& p) {
  Json j;
  j["resource"] = p.resource.id;
  j["kind"] = problemName(p.kind);
  j["message"] = p.message;
  return j;
}

}  // namespace

std::string mapInfoTable(const std::string& db_path,
                         const std::vector<store::SessionSummary>& sessions,
                         const std::vector<store::ResourceProblem>& problems, bool verified) {
  std::string out = format("%s: %zu session%s (schema version %d)\n", db_path.c_str(),
                           sessions.size(), sessions.size() == 1 ? "" : "s", store::kSchemaVersion);
  out += format("%4s  %-20s %-7s %9s %9s %8s %5s %5s %9s %9s %9s\n", "id", "name", "aligned",
                "keyframes", "optimised", "odometry", "loop", "prior", "resources", "path_m",
                "span_s");
  std::size_t keyframes = 0, edges = 0, resources = 0;
  double path_m = 0.0;
  for (const auto& s : sessions) {
    out += format("%4lld  %-20s %-7s %9zu %9zu %8zu %5zu %5zu %9zu %9.3f %9.3f\n",
                  static_cast<long long>(s.session.id), s.session.name.c_str(),
                  s.session.aligned ? "yes" : "no", s.keyframes, s.optimised_keyframes,
                  s.odometry_edges, s.loop_edges, s.prior_edges, s.resources, s.path_length_m,
                  s.last_timestamp_s - s.first_timestamp_s);
    keyframes += s.keyframes;
    edges += s.odometry_edges + s.loop_edges + s.prior_edges;
    resources += s.resources;
    path_m += s.path_length_m;
  }
  out += format("total: %zu keyframes, %zu edges, %zu resources, %.3f m of path\n", keyframes,
                edges, resources, path_m);
  if (verified) {
    out += problems.empty() ? std::string("resources: all present and unchanged\n")
                            : format("resources: %zu missing or changed\n", problems.size());
    for (const auto& p : problems) out += "  " + p.message + "\n";
  }
  return out;
}

std::string mapInfoJson(const std::string& db_path,
                        const std::vector<store::SessionSummary>& sessions,
                        const std::vector<store::ResourceProblem>& problems, bool verified) {
  Json rows = Json::array();
  for (const auto& s : sessions) rows.push_back(sessionSummaryJson(s));
  Json j;
  j["database"] = db_path;
  j["schema_version"] = store::kSchemaVersion;
  j["sessions"] = std::move(rows);
  if (verified) {
    Json list = Json::array();
    for (const auto& p : problems) list.push_back(problemJson(p));
    j["resource_problems"] = std::move(list);
  }
  return jsonFileText(j);
}

}  // namespace strata::apps

#include "cli/map_info.h"

#include <cstdarg>
#include <cstdio>

#include "core/json_text.h"
#include "store/schema.h"

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
  std::string out =
      "{\n  \"database\": " + jsonQuoted(db_path) +
      format(",\n  \"schema_version\": %d,\n  \"sessions\": [", store::kSchemaVersion);
  for (std::size_t i = 0; i < sessions.size(); ++i) {
    const auto& s = sessions[i];
    out += std::string(i == 0 ? "\n" : ",\n") + "    {\"id\": " + std::to_string(s.session.id) +
           ", \"name\": " + jsonQuoted(s.session.name) +
           ", \"source_folder\": " + jsonQuoted(s.session.source_folder) +
           format(
               ", \"aligned\": %s, \"keyframes\": %zu, \"optimised_keyframes\": %zu, "
               "\"odometry_edges\": %zu, \"loop_edges\": %zu, \"prior_edges\": %zu, "
               "\"resources\": %zu, \"resource_bytes\": %llu, \"path_length_m\": %.6f, "
               "\"first_timestamp_s\": %.6f, \"last_timestamp_s\": %.6f}",
               s.session.aligned ? "true" : "false", s.keyframes, s.optimised_keyframes,
               s.odometry_edges, s.loop_edges, s.prior_edges, s.resources,
               static_cast<unsigned long long>(s.resource_bytes), s.path_length_m,
               s.first_timestamp_s, s.last_timestamp_s);
  }
  out += sessions.empty() ? "]" : "\n  ]";
  if (verified) {
    out += ",\n  \"resource_problems\": [";
    for (std::size_t i = 0; i < problems.size(); ++i) {
      out += std::string(i == 0 ? "\n" : ",\n") +
             "    {\"resource\": " + std::to_string(problems[i].resource.id) + ", \"kind\": \"" +
             problemName(problems[i].kind) + "\", \"message\": " + jsonQuoted(problems[i].message) +
             "}";
    }
    out += problems.empty() ? "]" : "\n  ]";
  }
  return out + "\n}\n";
}

}  // namespace strata::apps

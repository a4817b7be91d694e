#include "objects_command.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>

#include "strata/core/error.h"
#include "strata/core/statistics.h"
#include "json.h"
#include "machine_info.h"
#include "strata/objects/object_database.h"
#include "objects_scene.h"
#include "summary.h"
#include "bench_timing.h"

namespace strata::bench {
namespace {

constexpr int kMatchedShapes = 5;  // the queries are views of models 1..5, in every N >= 5

Json stats(const std::vector<double>& values) {
  return Json::object()
      .set("calls", static_cast<int>(values.size()))
      .set("median", median(values))
      .set("p90", quantile(values, 0.9))
      .set("mean", mean(values));
}

struct Query {
  int shape = 0;  // index into the shapes; its model's id is shape + 1
  ObjectSession session;
};

/// Models 1..n, each founded by the complete view of its shape (observeObject timed).
std::vector<objects::ObjectModel> buildModels(const std::vector<BenchShape>& shapes,
                                              const objects::DatabaseConfig& config,
                                              std::vector<double>& observe_ms) {
  std::vector<objects::ObjectModel> models;
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const int id = static_cast<int>(i) + 1;
    const ObjectSession s = objectSession(shapes[i], 17.0 * id, View::kComplete, id);
    if (s.segments.empty()) throw Error("shape " + std::to_string(id) + " yielded no segment");
    const Clock::time_point start = Clock::now();
    const objects::ObjectObservation o =
        objects::observeObject(s.map, s.surface, s.segments.front(), id, config.observation);
    observe_ms.push_back(msSince(start));
    models.push_back(objects::foundModel(id, o, config.model));
    std::fprintf(stderr, "strata-bench objects: model %d/%zu (%zu segments)\r", id, shapes.size(),
                 s.segments.size());
  }
  std::fprintf(stderr, "\n");
  return models;
}

/// One stage call of each kind per query: its main segment against its own model.
Json stageTimes(const std::vector<Query>& queries, const std::vector<objects::ObjectModel>& models,
                const objects::DatabaseConfig& config, std::vector<double> observe_ms) {
  std::vector<double> register_ms, prepare_ms, prepared_ms, consistency_ms, merge_ms, refresh_ms;
  objects::RegistrationConfig registration = config.registration;
  registration.voxel_size_m = queries.front().session.map.config().voxel_size_m;
  const float spacing_m = config.observation.sample_spacing_voxels * registration.voxel_size_m;
  for (const Query& q : queries) {
    Clock::time_point start = Clock::now();
    const objects::ObjectObservation o = objects::observeObject(
        q.session.map, q.session.surface, q.session.segments.front(), 1000, config.observation);
    observe_ms.push_back(msSince(start));
    objects::ObjectModel model = models[static_cast<std::size_t>(q.shape)];
    start = Clock::now();
    const objects::RegistrationResult r =
        objects::registerSurfaces(o.surface_O, model.surface_M, registration);
    register_ms.push_back(msSince(start));
    // The same registration on clouds prepared beforehand (what the database does: a segment
    // once for all its candidates, a model once until it changes).
    start = Clock::now();
    const objects::SurfaceFeatures observed(o.surface_O, registration);
    const objects::SurfaceFeatures modelled(model.surface_M, registration);
    prepare_ms.push_back(msSince(start));
    start = Clock::now();
    objects::registerSurfaces(observed, modelled, registration);
    prepared_ms.push_back(msSince(start));
    start = Clock::now();
    objects::checkConsistency(model, o, r.T_target_source, q.session.map, config.consistency);
    consistency_ms.push_back(msSince(start));
    start = Clock::now();
    objects::mergeObservation(model, o, r.T_target_source, config.model);
    merge_ms.push_back(msSince(start));
    start = Clock::now();
    objects::refreshModel(model, spacing_m, config.model);
    refresh_ms.push_back(msSince(start));
  }
  return Json::object()
      .set("observe_object", stats(observe_ms))
      .set("register_surfaces", stats(register_ms))
      .set("prepare_features_both_clouds", stats(prepare_ms))
      .set("register_prepared", stats(prepared_ms))
      .set("check_consistency", stats(consistency_ms))
      .set("merge_observation", stats(merge_ms))
      .set("refresh_model", stats(refresh_ms));
}

struct SizeResult {
  int models = 0;
  std::vector<double> ms, candidates, registrations;
  std::vector<double> matched_ms;  // ms of the segments not skipped
  int segments = 0, skipped = 0, new_models = 0, matched_own = 0, matched_other = 0;
  int main_segments = 0, main_matched_own = 0;
};

/// Every query session added to its own copy of the database of the first n models.
SizeResult runSize(int n, const std::vector<objects::ObjectModel>& models,
                   const std::vector<Query>& queries, const objects::DatabaseConfig& config) {
  std::vector<int> sessions;
  for (int i = 1; i <= n; ++i) sessions.push_back(i);
  const objects::ObjectDatabase base = objects::ObjectDatabase::fromParts(
      config, std::vector<objects::ObjectModel>(models.begin(), models.begin() + n), sessions);
  base.prepareModels();  // as a database in use: its models prepared at earlier sessions
  SizeResult r;
  r.models = n;
  int session = 1000;
  for (const Query& q : queries) {
    objects::ObjectDatabase db = base;
    const auto outcomes =
        db.addSession(++session, q.session.map, q.session.surface, q.session.segments);
    for (const objects::SegmentOutcome& o : outcomes) {
      ++r.segments;
      r.ms.push_back(o.ms);
      if (!o.skipped.empty()) {
        ++r.skipped;
        continue;
      }
      r.matched_ms.push_back(o.ms);
      r.candidates.push_back(o.candidates);
      r.registrations.push_back(o.registrations);
      const bool own = !o.new_model && o.model_id == q.shape + 1;
      r.new_models += o.new_model ? 1 : 0;
      r.matched_own += own ? 1 : 0;
      r.matched_other += (!o.new_model && !own) ? 1 : 0;
      if (o.segment_id == q.session.segments.front().id) {
        ++r.main_segments;
        r.main_matched_own += own ? 1 : 0;
      }
    }
  }
  std::fprintf(stderr, "strata-bench objects: N = %d: %.1f ms per segment (median)\n", n,
               median(r.ms));
  return r;
}

Json sizeJson(const SizeResult& r, int queries) {
  return Json::object()
      .set("models", r.models)
      .set("query_sessions", queries)
      .set("segments", r.segments)
      .set("skipped_segments", r.skipped)
      .set("ms_per_segment", Json::object()
                                 .set("median", median(r.ms))
                                 .set("p90", quantile(r.ms, 0.9))
                                 .set("mean", mean(r.ms)))
      .set("prefilter_candidates_mean", mean(r.candidates))
      .set("registrations_mean", mean(r.registrations))
      // Registration dominates: what one candidate costs, converged or not.
      .set("ms_per_candidate",
           mean(r.candidates) > 0.0 ? mean(r.matched_ms) / mean(r.candidates) : 0.0)
      .set("new_models", r.new_models)
      .set("matched_own_model", r.matched_own)
      .set("matched_other_model", r.matched_other)
      .set("main_segments", r.main_segments)
      .set("main_segments_matched_own_model", r.main_matched_own);
}

/// time(big) / time(small) against big / small, for the largest and smallest N >= 5.
Json growthJson(const std::vector<SizeResult>& results) {
  const SizeResult* small = nullptr;
  for (const SizeResult& r : results) {
    if (r.models >= kMatchedShapes && (small == nullptr || r.models < small->models)) small = &r;
  }
  const SizeResult& big = results.back();
  if (small == nullptr || small == &big) return Json();
  const auto ratio = [](double a, double b) { return b > 0.0 ? a / b : 0.0; };
  return Json::object()
      .set("from_models", small->models)
      .set("to_models", big.models)
      .set("models_ratio", ratio(big.models, small->models))
      .set("median_ms_ratio", ratio(median(big.ms), median(small->ms)))
      .set("mean_ms_ratio", ratio(mean(big.ms), mean(small->ms)))
      .set("candidates_ratio", ratio(mean(big.candidates), mean(small->candidates)))
      .set("registrations_ratio", ratio(mean(big.registrations), mean(small->registrations)));
}

}  // namespace

CLI::App* addObjectsCommand(CLI::App& app, ObjectsBenchOptions& o) {
  CLI::App* c = app.add_subcommand("objects", "Object database: matching time against N models");
  c->add_option("--sizes", o.sizes, "Database sizes N (models), increasing")
      ->delimiter(',')
      ->capture_default_str();
  c->add_option("--yaws", o.yaws, "Query views per matched shape")->capture_default_str();
  c->add_option("--out", o.out_path, "Also write the JSON here");
  return c;
}

int runObjectsBench(const ObjectsBenchOptions& o) {
  try {
    if (o.sizes.empty() || !std::is_sorted(o.sizes.begin(), o.sizes.end()) || o.sizes.front() < 1 ||
        o.yaws < 1) {
      throw InputError("--sizes must be increasing and >= 1, --yaws >= 1");
    }
    const std::string load_at_start = loadAverage();
    const objects::DatabaseConfig config;
    const int max_models = o.sizes.back();
    const std::vector<BenchShape> shapes = benchShapes(std::max(max_models, kMatchedShapes));
    std::vector<double> observe_ms;
    const Clock::time_point build_start = Clock::now();
    const std::vector<objects::ObjectModel> models = buildModels(shapes, config, observe_ms);
    const double build_s = msSince(build_start) / 1000.0;
    std::vector<Query> queries;
    for (int shape = 0; shape < kMatchedShapes; ++shape) {
      for (int y = 0; y < o.yaws; ++y) {
        const double yaw_deg = 17.0 * (shape + 1) + 75.0 + 130.0 * y;
        queries.push_back({shape, objectSession(shapes[static_cast<std::size_t>(shape)], yaw_deg,
                                                View::kHalf, 1000)});
        if (queries.back().session.segments.empty()) throw Error("a query yielded no segment");
      }
    }
    std::vector<SizeResult> results;
    for (const int n : o.sizes) results.push_back(runSize(n, models, queries, config));
    Json sizes = Json::array();
    for (const SizeResult& r : results) sizes.push(sizeJson(r, static_cast<int>(queries.size())));
    // Self-check: every query was processed and, from N = 5 on, the main segments found their
    // own model no less often than against the smallest such database (more models must not
    // take matches away from the right one).
    bool checks_passed = true;
    int reference_main = -1;
    for (const SizeResult& r : results) {
      checks_passed = checks_passed && r.segments >= static_cast<int>(queries.size());
      if (r.models < kMatchedShapes) continue;
      if (reference_main < 0) reference_main = r.main_matched_own;
      checks_passed = checks_passed && r.main_matched_own >= reference_main;
    }
    Json kinds = Json::array();
    for (int i = 0; i < max_models; ++i) {
      const BenchShape& s = shapes[static_cast<std::size_t>(i)];
      kinds.push(Json::object()
                     .set("model", i + 1)
                     .set("kind", sim::shapeKindName(s.spec.kind))
                     .set("size_m",
                          Json::numbers({s.spec.size_m.x(), s.spec.size_m.y(), s.spec.size_m.z()}))
                     .set("albedo", Json::numbers({double(s.albedo[0]), double(s.albedo[1]),
                                                   double(s.albedo[2])})));
    }
    Json report =
        Json::object()
            .set("benchmark", "objects")
            .set("machine", machineInfo("host CPU (PCL)", load_at_start))
            .set("settings", Json::object()
                                 .set("sizes", Json::numbers(std::vector<double>(o.sizes.begin(),
                                                                                 o.sizes.end())))
                                 .set("voxel_size_m", 0.02)
                                 .set("queries", static_cast<int>(queries.size()))
                                 .set("query_views", "half of the shape (its -y side), new yaw")
                                 .set("model_views", "complete (every side observed)")
                                 .set("model_build_seconds", build_s)
                                 .set("database_config", "defaults (object_database.h)")
                                 .set("models", kinds))
            .set("results", sizes)
            .set("growth", growthJson(results))
            .set("stages_ms", stageTimes(queries, models, config, observe_ms))
            .set("checks_passed", checks_passed);
    emitReport(report, o.out_path);
    return checks_passed ? 0 : 1;
  } catch (const InputError& e) {
    std::fprintf(stderr, "strata-bench objects: input error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "strata-bench objects: error: %s\n", e.what());
    return 1;
  }
}

}  // namespace strata::bench
